#include "harness/report/report_messages.hpp"

#include <map>
#include <utility>

#include "harness/judge/engine_messages.hpp"
#include "harness/report/report_format.hpp"

namespace dropcheck {
namespace {

struct Count {
  std::int64_t times = 0, runs = 0;
  const EngineInfo* info = nullptr;
};

// Adds what `run` printed to `counts`, keyed by engine and line.
void count_run(const Trajectory& run, const EngineInfo& info,
               std::map<std::pair<std::string, std::string>, Count>& counts) {
  const auto bump = [&](const std::string& line, std::int64_t times) {
    Count& c = counts[{info.name, line}];
    c.times += times;
    ++c.runs;
    c.info = &info;
  };
  for (const Trajectory::Message& m : run.messages) bump(m.text, m.count);
  if (run.other_lines > 0) bump("(other lines)", run.other_lines);
}

}  // namespace

std::string engine_messages_section(const ReportInput& in) {
  std::map<std::pair<std::string, std::string>, Count> counts;
  for (const SceneEvaluation& se : in.scenes)
    for (const EngineEvaluation& ev : se.engines) {
      for (const StepEvaluation& s : ev.sweep) count_run(s.run, ev.info, counts);
      count_run(ev.fine, ev.info, counts);
    }
  if (counts.empty()) return {};
  MarkdownTable t({"engine", "line", "times", "runs", "what it means"}, "llrrl");
  for (const auto& [key, c] : counts)
    t.add({key.first, "`" + key.second + "`", std::to_string(c.times), std::to_string(c.runs),
           message_meaning(*c.info, key.second)});
  return "## What the engines printed\n\nLines the engines wrote to stderr during this report's "
         "runs, each distinct line counted over every run instead of shown (each run keeps its "
         "first " +
         std::to_string(Trajectory::kKeptMessages) +
         " distinct lines); a contact verdict that no member of its law explains quotes "
         "them.\n\n" +
         t.str() + "\n";
}

}  // namespace dropcheck
