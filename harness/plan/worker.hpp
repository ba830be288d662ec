// A shard's cells run in worker processes instead of one process per run: each worker, forked
// once, takes cell after cell from a queue the workers share, runs each in its own process (no
// further fork) and streams each record back. A cell during which a worker dies or that outlasts
// the run time limit is run again the per-cell way (run_cell with each run in a child process), so
// its record (crashed, timed out) is the one the per-cell path writes; a new worker takes the dead
// one's place. The records are therefore the same bytes either way, at the cost of one fork per
// worker instead of one per cell (bench/sweep_scale.cpp prints what that saves).
#pragma once

#include <chrono>
#include <functional>
#include <vector>

#include "harness/plan/cell_record.hpp"

namespace dropcheck {

// How long the parent waits for the worker's next record before it counts the worker as hung: the
// run time limit of a cell run alone (kDefaultRunTimeLimitSeconds) and a minute for its measures.
inline constexpr std::chrono::milliseconds kWorkerSilenceLimit{660'000};

// What the worker path did, for progress lines and tests.
struct WorkerStats {
  std::size_t workers = 0;      // worker processes started
  std::size_t rerun_alone = 0;  // cells the worker died in or was silent past the limit in
};

// The records of `cells` (indices into `plan`), in the order given, from `jobs` workers side by
// side that pull the next cell from one queue (a cell costs what its engine and step make it, so a
// fixed share per worker would leave the fastest idle); `done(i, record)` is called as each
// arrives, in the order they finish. A worker silent for `silence` is killed, and a worker that
// dies or is killed has its cell run alone and a new worker take its place while cells are left.
// The records do not depend on `jobs`.
std::vector<CellRecord> run_cells_in_worker(
    const Plan& plan, const std::vector<std::size_t>& cells,
    const std::function<void(std::size_t, const CellRecord&)>& done = {},
    std::chrono::milliseconds silence = kWorkerSilenceLimit, WorkerStats* stats = nullptr,
    int jobs = 1);

// The cores this process may run on (its CPU affinity: what a Slurm task or taskset gives it).
int usable_cores();

}  // namespace dropcheck
