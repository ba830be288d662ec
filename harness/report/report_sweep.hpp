// A sweep's merged results (docs/results.md) as a report: for each scene and engine, a map of the
// cells over the sweep's first two axes, one showing how each run ended with the step the theory
// says is the largest stable one drawn across it, one showing the error against the closed form in
// decades; the cells that failed, with their cause; and, where the sweep was timed, the medians per
// engine and CPU model (never pooled across models). `dropcheck report --results FILE`; the file is
// read by sweep_results.hpp.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "harness/report/sweep_results.hpp"

namespace dropcheck {

// Writes README.md and the maps (SVG, by gnuplot) into `dir`, which must exist.
void write_sweep_report(const std::vector<SweepCell>& cells, const std::string& results,
                        const std::string& dir,
                        const std::function<void(const std::string&)>& progress = {});

}  // namespace dropcheck
