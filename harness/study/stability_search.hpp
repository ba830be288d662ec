// The search for the largest stable step of one engine on one scene, by bisection on h
// (stability_search.cpp).
#pragma once

#include <cstdint>
#include <limits>
#include <optional>

#include "harness/core/engine.hpp"
#include "harness/judge/stability_classify.hpp"

namespace dropcheck {

// How the step search runs (stability_search.cpp).
struct SearchOptions {
  double rel_tol = 2e-3;              // bisection stops when hi/lo - 1 is below this
  std::int64_t horizon_steps = 3000;  // each probe simulates min(duration, horizon_steps*h0)
  double max_h = 1.0;                 // largest step tried: min(max_h, duration/8)
  int max_halvings = 10;              // from an unstable h0 down to h0/2^10 at most
  double max_probe_growth = 16.0;     // a probe below h0 runs at most 16x the steps of h0's probe
  std::int64_t max_probe_steps = 400000;  // and never more steps than this
};

// Result of the search for the largest stable step of one engine on one scene.
struct StepSearch {
  static constexpr double none = std::numeric_limits<double>::quiet_NaN();
  double max_stable_dt = none;    // largest h found stable (NaN: no stable h found)
  double min_unstable_dt = none;  // smallest h above it found unstable (NaN: none up to the cap)
  double min_stable_dt = none;    // set when h0 fails at small h (frozen): smallest stable h above
  std::optional<FailureMode> limit;  // the failure at min_unstable_dt
  double start = 0.0;                // h0, the step the search started from
  double horizon = 0.0;  // simulated seconds of each probe (before rounding up to whole h)
  double cap = 0.0;      // largest h tried
  int probes = 0;        // runs made
};

// Searches the largest stable h for engines made by `make` on `scene` (each probe classified by
// classify_engine_run, with the engine's scalar and contact laws), starting at h0 (stable:
// double up to the cap, then bisect; unstable: halve down within the step budget, then bisect;
// frozen only: double up to the first stable h, then as if stable). Each probe runs the scene
// for duration' = ceil(horizon/h)*h, horizon = min(duration, horizon_steps*h0).
StepSearch search_max_stable_dt(const EngineFactory& make, const Scene& scene, double h0,
                                const SearchOptions& options = {},
                                const ClassifyOptions& classify = {});

// The record_every that keeps a run of `steps` steps at most 20000 samples (frozen and growth
// detection work on samples; a long run need not keep every step).
std::int64_t stability_record_every(std::int64_t steps);
// The record_every of a stability run of `scene` at h: every step, up to 200000, on a scene that
// holds a slide, a bounce or a stack (its contact laws are judged step by step), else the above.
std::int64_t stability_record_every(const Scene& scene, double h);

// The scene with its duration set to ceil(horizon/h)*h: whole steps of h (scene_for_step.duration/h
// rounds to an integer), at least one step.
Scene scene_for_step(const Scene& scene, double h, double horizon);

}  // namespace dropcheck
