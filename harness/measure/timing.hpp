// Run-time measurement: wall time per simulated second, as the minimum and median of repeated runs
// after a warm-up, on a scene replicated until one run is long enough to time.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"

namespace dropcheck {

struct TimingOptions {
  double min_run_seconds = 0.02;  // replicate the scene until one run takes at least this long
  int warmups = 1;
  int repeats = 5;
  int max_replicas = 4096;
};

struct Timing {
  std::string engine;
  double h = 0.0;
  int replicas = 1;              // copies of the scene's dynamic bodies in one timed run
  double min_per_sim_s = 0.0;    // wall seconds per simulated second, per copy of the scene
  double median_per_sim_s = 0.0;
  double bare_min_per_sim_s = 0.0;  // the engine's bare step() loop, no forces/reads/sampling
  // Harness overhead: (full loop - bare loop) / bare loop, from the minima.
  double overhead() const { return bare_min_per_sim_s > 0 ? min_per_sim_s / bare_min_per_sim_s - 1 : 0; }
};

// The scene copied `copies` times side by side: every body (static floors too, so that each copy
// lands on its own floor), copy c shifted by c*(x extent of the scene + 10 m) along x, so that the
// copies never touch and a planar scene stays planar; every force duplicated onto the copies (a
// spring's anchor shifted with its body).
Scene replicate(const Scene& scene, int copies);

// Times each engine on `scene` at step h. Engines run in alternating order within each repeat so
// that drift of the machine (frequency, cache, other load) hits all alike.
std::vector<Timing> time_engines(const std::vector<std::pair<std::string, EngineFactory>>& engines,
                                 const Scene& scene, double h, const TimingOptions& options = {});

}  // namespace dropcheck
