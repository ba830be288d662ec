// Numerical stability: classify one run as stable or by its failure, search the largest stable step
// per engine by bisection on h, and the theoretical edge of a spring under each damping order.
// Engine-neutral: works on Scene, Trajectory and the engine's declared scalar and law only.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

// How a run failed, in order of severity (a run's verdict lists the severest first).
enum class FailureMode {
  engine_error,      // the engine threw or reported an error (RunStatus::engine_error)
  non_finite,        // a NaN/Inf state (RunStatus::non_finite)
  unbounded_growth,  // energy or speed beyond what the physics allows
  tunnelled,         // a body ended below (or deep inside) a body it started above; contacts on
  frozen,            // a coordinate constant over many steps while the physics says it moves
                     // by more than half a float spacing and the scene's tolerance
  clamped,           // the engine clamped a speed (Trajectory::clamped_steps > 0)
};

// Short name of a failure mode ("NaN/Inf", "frozen", ...), as tables print it.
const char* to_string(FailureMode mode);

// One failure of one run: where it showed first and a sentence saying what happened.
struct Failure {
  FailureMode mode = FailureMode::engine_error;
  std::string body;        // the body concerned; "" for the whole run
  std::int64_t step = -1;  // first step where it showed
  std::string what;        // a sentence, without the engine's name in front
};

// The classification of one run: stable when it has no failure.
struct Verdict {
  std::vector<Failure> failures;  // severest first, then by step
  bool stable() const { return failures.empty(); }
};

// Thresholds of the classifier (the reasoning behind each is in stability_classify.cpp).
struct ClassifyOptions {
  double growth_factor = 10.0;     // late-window vs early-window peak oscillation energy
  double energy_factor = 1e6;      // peak oscillation energy vs initial
  double speed_slack = 0.01;       // relative slack on the free-flight speed bound
  std::int64_t frozen_steps = 20;  // fewest steps of a constant coordinate that count as frozen
  double contact_gain = 0.5;       // energy gained in a contact scene vs its peak kinetic energy
};

// Classifies `run` of `scene` on an engine computing in `scalar`. Never throws for a failed run.
Verdict classify_run(const Scene& scene, const Trajectory& run, Scalar scalar,
                     const ClassifyOptions& options = {});

// "ours (f32)": the engine's name and scalar, as failure sentences start.
std::string engine_label(const std::string& engine, Scalar scalar);

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

// Searches the largest stable h for engines made by `make` on `scene`, starting at h0 (stable:
// double up to the cap, then bisect; unstable: halve down within the step budget, then bisect;
// frozen only: double up to the first stable h, then as if stable). Each probe runs the scene
// for duration' = ceil(horizon/h)*h, horizon = min(duration, horizon_steps*h0).
StepSearch search_max_stable_dt(const EngineFactory& make, Scalar scalar, const Scene& scene,
                                double h0, const SearchOptions& options = {},
                                const ClassifyOptions& classify = {});

// The record_every that keeps a run of `steps` steps at most 20000 samples (frozen and growth
// detection work on samples; a long run need not keep every step).
std::int64_t stability_record_every(std::int64_t steps);

// The scene with its duration set to ceil(horizon/h)*h: whole steps of h (scene_for_step.duration/h
// rounds to an integer), at least one step.
Scene scene_for_step(const Scene& scene, double h, double horizon);

// A linear spring on one body as the stability analysis sees it: w^2 = S/m, gamma = C/m, k drag.
struct SpringModel {
  double omega = 0.0;  // rad/s
  double gamma = 0.0;  // dashpot per unit mass, 1/s
  double k = 0.0;      // world damping rate, 1/s
};

// The linear springs (rest length 0) acting on body `index`, combined; nullopt if none or if one of
// them has a rest length (nonlinear: no single w).
std::optional<SpringModel> body_spring(const Scene& scene, std::size_t index);

// True when one step of `law` with spring force from the start-of-step state is stable at h
// (derivation in stability_theory.cpp).
bool spring_step_stable(Law law, const SpringModel& spring, double h);

// The largest h at which `law` is stable for `spring` (the first edge above h = 0).
double spring_max_stable_dt(Law law, const SpringModel& spring);

// The theoretical edge of `scene` under `law`: the smallest over bodies on linear springs
// (rest_length 0); nullopt when the scene has none (free flight is stable at every h).
std::optional<double> spring_theory_max_dt(const Scene& scene, Law law);

}  // namespace dropcheck
