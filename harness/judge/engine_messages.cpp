#include "harness/judge/engine_messages.hpp"

namespace dropcheck {

std::string message_meaning(const EngineInfo& info, const std::string& line) {
  for (const EngineInfo::KnownMessage& k : info.known_messages)
    if (line.rfind(k.starts, 0) == 0) return k.meaning;
  return {};
}

std::string engine_said(const Trajectory& run, const EngineInfo& info) {
  std::string text = run.messages_text();
  if (text.empty()) return text;
  for (const Trajectory::Message& m : run.messages)
    if (std::string meaning = message_meaning(info, m.text); !meaning.empty())
      return text + ": " + meaning;
  return text;
}

}  // namespace dropcheck
