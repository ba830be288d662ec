// `dropcheck check`'s verdicts for machines: a JUnit XML file (the shape CI systems' test reporters
// read: GitLab, Jenkins, GitHub) and a JSON file (docs/check.schema.json), one entry per scene x
// engine x check, and per scene x engine an engine could not run. The same results as the printed
// lines, in the same order; no time stamps, so the same run writes the same bytes.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "harness/study/checks.hpp"

namespace dropcheck {

// One printed line of `check`: a check's result, or an engine that could not run the scene.
struct CheckRecord {
  CheckResult result;
  bool skipped = false;
  std::string skipped_because;  // the engine's reason ("not planar", "no contacts")
};

// One engine's scenes at a glance (`check --engine X` ends with it): per scene, in order, whether
// every check passed (limits pass), the first that failed, or why the engine could not run it and
// the capability that would let it (capability_lifting, harness/core/engine.hpp).
struct SceneOutcome {
  std::string scene;
  std::string verdict;     // "passed", "failed", "skipped"
  int checks = 0;          // checks run (0 when skipped)
  std::string detail;      // the first failed check and its message; a skip's reason
  std::string capability;  // a skip a capability lifts: its protocol word
};
std::vector<SceneOutcome> engine_outcomes(const std::vector<CheckRecord>& records,
                                          const std::string& engine);

// "pass", "limit", "fail" or "skipped".
std::string verdict_word(const CheckRecord& r);

// <testsuites name="dropcheck check" tests= failures= skipped=>, one <testsuite> per scene in
// order of first appearance, one <testcase classname="SCENE.ENGINE" name="CHECK"> per record; a
// failure's <failure message="MESSAGE"> (its figures, first departure and cause), a skip's
// <skipped message="REASON"/>, a limit's cause in <system-out>. Text is escaped; what XML 1.0
// cannot carry (control characters, bytes that are not UTF-8) becomes U+FFFD.
void write_junit(std::ostream& out, const std::vector<CheckRecord>& records);

// {"schema": "dropcheck-check/1", "passed", "limits", "failed", "skipped", "results": [{"scene",
// "engine", "check", "verdict", "limit", "message"}]} (docs/check.schema.json).
void write_check_json(std::ostream& out, const std::vector<CheckRecord>& records);

}  // namespace dropcheck
