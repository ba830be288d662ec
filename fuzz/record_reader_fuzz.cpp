// Fuzz target: the two readers of a sweep's record lines (docs/results.md), on the input as a
// result file's text: merge's check of each line against its plan (harness/plan/merge.cpp:
// record_key, with the small fixed plan below, whose hash is that of the seeds' plan so that their
// records get past it) and the report's reader (harness/report/sweep_results.cpp:
// parse_sweep_results, what `report --results` reads). Every line must be taken or refused with
// InputError, a key taken must be one of the plan's, and a refusal's message must be short and
// inert (no control character, no invalid UTF-8). Anything else aborts: a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <unordered_set>

#include "harness/core/input_error.hpp"
#include "harness/plan/merge.hpp"
#include "harness/report/sweep_results.hpp"

namespace {

void require_inert(const dropcheck::InputError& e) {
  const std::string message = e.what();
  if (message.size() > 1024 || dropcheck::find_unsafe_byte(message) != std::string::npos)
    std::abort();
}

// The plan of tests/sweeps/example.toml (fuzz/regressions/record_reader/ holds records of it): its
// cells' keys, and its hash, without the scene's text (record_key reads neither).
dropcheck::Plan example_plan() {
  dropcheck::Plan p;
  p.scenes = {{"stiff_spring", "stiff_spring.toml", ""}};
  p.engines = {"ours", "bullet", "mujoco"};
  p.axes = {{dropcheck::AxisKind::timestep, "timestep", {"1/60", "1/20"}, 0},
            {dropcheck::AxisKind::scalar, "scalar", {"f32", "f64"}, 0}};
  p.hash = "e801ebd6d4de906a";
  return p;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const dropcheck::Plan plan = example_plan();
  static const std::unordered_set<std::string> keys = dropcheck::cell_keys(plan);
  const std::string text(reinterpret_cast<const char*>(data), size);
  long long n = 0;
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(at, end - at);
    at = end + 1;
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    try {
      if (!keys.count(dropcheck::record_key(plan, keys, "fuzz.jsonl", n, line))) std::abort();
    } catch (const dropcheck::InputError& e) {
      require_inert(e);
    }
  }
  try {
    (void)dropcheck::parse_sweep_results(text, "fuzz.jsonl");
  } catch (const dropcheck::InputError& e) {
    require_inert(e);
  }
  return 0;
}
