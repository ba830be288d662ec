// The classification of one run (stability_classify.cpp): its status, growth, tunnelling, frozen
// coordinates and speed clamps, each a Failure; and the model of one body's forces the detectors
// share (stability_growth.hpp, stability_motion.hpp).
#pragma once

#include <cstdint>
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
  off_contact_law,   // a slide, bounce, stack or tumbling landing left its contact law
                     // (docs/contact.md): the step no longer gives the physics the engine is
                     // judged by
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
  // m: how far the engine's contacts may lift a resting body per contact level (its rest offset
  // and stated stillness, classify_engine_run): the energy of that lift is not growth.
  double resting_lift = 0.0;
};

// Classifies `run` of `scene` on an engine computing in `scalar`. Never throws for a failed run.
Verdict classify_run(const Scene& scene, const Trajectory& run, Scalar scalar,
                     const ClassifyOptions& options = {});

// "ours (f32)": the engine's name and scalar, as failure sentences start.
std::string engine_label(const std::string& engine, Scalar scalar);

namespace stability_detail {

// The constant part and the springs acting on one body, combined (all forces of the scene):
//   m*x'' = m*accel - stiffness*(x - anchor) - dashpot*x'   (rest_length 0 springs)
struct BodyLaw {
  Vec3 accel = Vec3::Zero();   // g + F/m, m/s^2
  double stiffness = 0.0;      // S, N/m
  Vec3 anchor = Vec3::Zero();  // stiffness-weighted anchor, m
  double dashpot = 0.0;        // C, N*s/m
  bool nonlinear = false;      // a spring with a rest length acts on it
};

// The BodyLaw of body `index`.
BodyLaw body_law(const Scene& scene, std::size_t index);

// Distance between |x| and the next representable number above it in `scalar` (m).
double float_spacing(double x, Scalar scalar);

}  // namespace stability_detail

}  // namespace dropcheck
