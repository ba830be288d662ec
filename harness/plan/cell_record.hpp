// One cell of a plan, run and measured: its record, one line of JSON (docs/results.md).
//
// A record is a pure function of the plan's cell, this build and the engines' libraries: the same
// cell gives the same bytes on every run (no wall time unless the plan measures timing, and then
// the figures that depend on it sit under "timing", marked, with the CPU model and host). What
// the engine does is a result, never a failure of the sweep: an engine that blows up, aborts,
// hangs or cannot run the cell leaves a record saying so.
#pragma once

#include <string>

#include "harness/plan/plan.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {

inline constexpr const char* kRecordFormat = "dropcheck-record/1";

struct CellRecord {
  std::string status;  // "ok", a run status ("non-finite", "crashed", ...), "skipped", "invalid"
  std::string line;    // the record: one JSON object, no trailing newline
};

// Runs cell `cell` of `plan` and records it; `isolation` says where its run happens (a shard's
// worker runs it in its own process; a cell the worker died in, in a child of its own), and a
// child-process run ends at `time_limit_seconds` of wall time (<= 0: kDefaultRunTimeLimitSeconds).
CellRecord run_cell(const Plan& plan, const Cell& cell,
                    Isolation isolation = Isolation::process_default,
                    double time_limit_seconds = 0.0);

// What a cell's record depends on besides the plan's hash, as 16 hex digits: its key, its scene's
// text, the measures, and this build (key, flags, commit). Two plans that share a cell share this.
std::string cell_identity(const Plan& plan, const Cell& cell);

// A record kept for `cell_identity` (a cache, shard.hpp) made this plan's: its plan field set to
// plan.hash, the rest unchanged byte for byte. Empty when `line` is not a record of this cell made
// by this build.
CellRecord adopt_record(const Plan& plan, const Cell& cell, const std::string& line);

}  // namespace dropcheck
