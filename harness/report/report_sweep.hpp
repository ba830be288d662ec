// A sweep's merged results (docs/results.md) as a report: for each scene and engine, a map of the
// cells over the sweep's first two axes, one showing how each run ended with the step the theory
// says is the largest stable one drawn across it, one showing the error against the closed form in
// decades; the cells that failed, with their cause; and, where the sweep was timed, the medians per
// engine and CPU model (never pooled across models). `dropcheck report --results FILE`.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace dropcheck {

// What the report reads of one record.
struct SweepCell {
  std::string key, scene, engine, status, reason;
  std::vector<std::pair<std::string, std::string>> axes;  // in the sweep's order
  std::optional<double> error;                            // error.closed_form.max_dx (m)
  std::optional<double> theory_max_h;                     // stability.theory_max_h (s)
  std::string law_unstable;
  std::optional<double> ns_per_body_step;  // timing (wall time)
  std::string cpu;
};

// Reads a result file. Throws InputError naming the file and line for a line that is not a record.
std::vector<SweepCell> read_sweep_results(const std::string& path);

// Writes README.md and the maps (SVG, by gnuplot) into `dir`, which must exist.
void write_sweep_report(const std::vector<SweepCell>& cells, const std::string& results,
                        const std::string& dir,
                        const std::function<void(const std::string&)>& progress = {});

}  // namespace dropcheck
