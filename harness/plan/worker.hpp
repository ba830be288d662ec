// A shard's cells run in one worker process instead of one process per run: the worker, forked
// once, runs cell after cell in its own process (no further fork) and streams each record back. A
// cell during which the worker dies or that outlasts the run time limit is run again the per-cell
// way (run_cell with each run in a child process), so its record (crashed, timed out) is the one
// the per-cell path writes; a new worker continues at the next cell. The records are therefore the
// same bytes either way, at the cost of one fork per shard instead of one per cell (about 2 ms a
// cell: bench/sweep_scale.cpp).
#pragma once

#include <functional>
#include <vector>

#include "harness/plan/cell_record.hpp"

namespace dropcheck {

// The records of `cells` (indices into `plan`), in the order given; `done(i, record)` is called as
// each arrives.
std::vector<CellRecord> run_cells_in_worker(
    const Plan& plan, const std::vector<std::size_t>& cells,
    const std::function<void(std::size_t, const CellRecord&)>& done = {});

}  // namespace dropcheck
