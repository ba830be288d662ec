// The own-law verdict (oracle 2), computed in one place for `check`, `report`, the regression
// tiers and the adapter tests: does one run follow the discrete law its engine declares?
//
// The run is compared with its law iterated in the engine's own arithmetic
// (harness/oracles/own_arithmetic.hpp); the distance is the Euclidean norm per body, worst over
// samples and bodies, positions and velocities apart. A clamp the engine reports (Box2D's speed
// clamp) ends the comparison at the step before: the law does not model it, and it is named.
// The long-double law gives the precision part: what the engine's scalar costs.
#pragma once

#include <optional>
#include <string>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

// How far a run may depart from its own law at one step h, and the rule that says so.
struct OwnLawTolerance {
  double x = 0.0;    // m
  double v = 0.0;    // m/s
  std::string rule;  // "4 ulps of 12.3 m (f32, operation order copied)"

  // Both bounds finite. A law that reaches Inf or NaN has none (its scale is NaN): nothing follows.
  bool finite() const;
};

// THE answer to "what is the own-law tolerance of engine E at step h": from E's arithmetic and its
// law's trajectory at h (`own_law` = predict_own_arithmetic(info, scene, h)). Copied order:
// tolerance::kCopiedUlps ulps of the largest |x| or |v|; otherwise tolerance::kStepUlps ulps of it
// per step. An error-controlled engine's is its accuracy budget over `engine_steps` of its own
// steps (Trajectory::engine_steps; at least own_law.steps are counted): own_law.cpp derives it.
OwnLawTolerance own_law_tolerance(const EngineInfo& info, const Trajectory& own_law,
                                  std::int64_t engine_steps = 0);

// One run against its own law.
struct OwnLawVerdict {
  std::string engine;
  std::string law;          // to_string(info.law)
  std::string failure;      // the run did not finish (status and reason); "" when it did
  double residual_x = 0.0;  // max |x - own law| (m)
  double residual_v = 0.0;  // max |v - own law| (m/s)
  std::size_t worst_sample = 0, worst_body = 0;  // where the larger relative departure is
  OwnLawTolerance tolerance;
  double precision = 0.0;           // max |own-arithmetic law - long-double law| (m): scalar cost
  std::int64_t clamped_from = -1;   // first step the engine clamped a speed; compared before it
  std::int64_t compared_steps = 0;  // last step compared
  // For a run that rotates: its orientation and angular velocity against its rotational member
  // (harness/core/rotation_law.hpp), as the geodesic angle and |w - w_law|, worst over the samples
  // compared. Bounded like the linear residual, times the law's amplification (own_rotation.hpp).
  bool rotation = false;
  std::string rotation_law;      // to_string(info.rotation_law)
  double residual_angle = 0.0;   // rad
  double residual_w = 0.0;       // rad/s
  double tolerance_angle = 0.0;  // rad
  double tolerance_w = 0.0;      // rad/s
  std::string rotation_rule;     // "16 ulps per step x 10000 steps x amplification 858 (f64)"

  // The run finished and stays within a finite tolerance of its own law.
  bool follows() const;
  // The rotation's tolerance is finite and at most tolerance::kMaxRotationTolerance: the rotation
  // is judged. A non-finite one (the law blew up) fails the verdict; a larger finite one (rounding
  // amplified past what an angle can say) leaves the rotation unjudged, and the sentence says so.
  bool rotation_judged() const;
  // "max |x - law| 0 m, |v - law| 0 m/s (tolerance 4 ulps ...); precision part 1.2e-6 m; ..."
  std::string sentence() const;
};

// Judges `run` against `own` (its law in its arithmetic) and `exact` (the long-double law), all
// of one scene at one h.
OwnLawVerdict judge_own_law(const EngineInfo& info, const Trajectory& run, const Trajectory& own,
                            const Trajectory& exact);

// Predicts both laws of `info` for `run`'s scene and step and judges the run.
OwnLawVerdict judge_own_law(const EngineInfo& info, const Scene& scene, const Trajectory& run);

// The member of the law family (harness/core/law.hpp) that `run` follows to the not-copied
// tolerance of its scalar, if any: what a scheme that left its declared law does instead.
std::optional<Law> fitting_law(const EngineInfo& info, const Scene& scene, const Trajectory& run);

// A reader's name for a member of the family: "explicit Euler, damping after the forces",
// "semi-implicit Euler, damping after the position update (ODE's order)".
std::string law_family_name(Law law);

// The samples of `t` recorded before step n (all of them when n < 0).
Trajectory before_step(const Trajectory& t, std::int64_t n);

}  // namespace dropcheck
