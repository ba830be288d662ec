// Blessing: turning fresh runs into the golden baselines (or any result set), but only when they
// pass the oracle checks. A baseline that is wrong physics must never become the truth.
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
};

// What bless did, for the command to print.
struct BlessOutcome {
  std::vector<std::string> refused;  // each failed oracle check (tier 3); nothing written if any
  std::vector<std::string> lines;    // per file: "new", "updated" or "unchanged", path and hash
};

// Makes the baseline of every scene on every engine, checks each with check_physics, and only if
// all pass writes them (atomically, file by file) to out_dir. A file whose numbers are unchanged is
// left untouched (same_data), so re-blessing at another commit or from another build keeps the bytes
// and the build key of the build that first wrote them. Throws InputError on a write error.
BlessOutcome bless(const std::vector<Scene>& scenes, const std::vector<NamedFactory>& engines,
                   const BlessOptions& options);

}  // namespace dropcheck
