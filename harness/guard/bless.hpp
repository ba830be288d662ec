// Blessing: turning fresh runs into the golden baselines, but only when they pass the oracle checks
// (a baseline that is wrong physics must never become the truth), or into any other result set,
// always, with failed tiers marked in the files, so that `dropcheck diff` can compare a new scheme.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "harness/guard/baseline.hpp"

namespace dropcheck {

// An engine name (as in the baseline file name) and how to make the engine.
using NamedFactory = std::pair<std::string, EngineFactory>;

// Where to write and what to record.
struct BlessOptions {
  std::string out_dir = "tests/baselines";  // the result set to (re)write
  std::string commit = "unknown commit";    // recorded in each file's provenance line
  BaselineOptions baseline;                 // sampling; --timing
  bool refuse_failed = false;               // refuse as for the golden set, wherever out_dir is
  std::string baselines_dir = "tests/baselines";  // the baselines tier 3 measures a new scheme from
  // The engine `dropcheck check` measures divergences from (ours-f64): with it, tier 3 asks the
  // measurement core where the stored sweep fails (check_physics); without it, it does not.
  EngineFactory reference;
};

// True when `dir` is the golden set, tests/baselines under the working directory.
bool is_golden_set(const std::string& dir);

// What bless did, for the command to print.
struct BlessOutcome {
  std::vector<std::string>
      refused;                     // golden set: each failed oracle check (tier 3); nothing written
  std::vector<std::string> lines;  // per file: "new", "updated" or "unchanged", path and hash
  std::vector<std::string> failed;  // elsewhere: each failed oracle check, written and marked
};

// DIR/<scene>.<engine>.txt with every character of the names outside [A-Za-z0-9._-] turned into
// '_' and a leading '.' prefixed with '_' (as the report names its plots): "../x" cannot leave DIR,
// an absolute name cannot either, and "/" or a NUL byte makes no path.
std::string baseline_path(const std::string& dir, const std::string& scene,
                          const std::string& engine);

// baseline_path of every scene on every engine, in order. Throws InputError when two pairs would
// share a file (the naming is not one-to-one: "a/b" and "a_b"), naming both scenes.
std::vector<std::string> baseline_paths(const std::vector<Scene>& scenes,
                                        const std::vector<std::string>& engines,
                                        const std::string& dir);

// Makes the baseline of every scene on every engine and checks each with check_physics (against
// the same scene and engine in options.baselines_dir, when there is one). Into the
// golden set (or with refuse_failed) it writes only if all pass; anywhere else it writes every
// file, a failed check recorded in it ("# FAILED physics: ...") and in its log line. A file whose
// numbers are unchanged is left untouched (same_data), so re-blessing at another commit or from
// another build keeps the bytes and the build key of the build that first wrote them. Throws
// InputError on a write error.
BlessOutcome bless(const std::vector<Scene>& scenes, const std::vector<NamedFactory>& engines,
                   const BlessOptions& options);

}  // namespace dropcheck
