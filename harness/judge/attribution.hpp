// Attribution: why two engines' trajectories of one free-flight scene differ, and which engine is
// at fault when the laws do not explain it.
//
// Write x_E, x_R for the two engines' positions, L_E, L_R for their exact discrete laws (long
// double, harness/oracles/discrete_law.hpp) and A_E, A_R for the same laws in each engine's own
// arithmetic (harness/oracles/own_arithmetic.hpp), all at the same step. Then, sample by sample,
//   x_E - x_R = (L_E - L_R)                       law part: the scheme difference (O(h))
//             + [(A_E - L_E) - (A_R - L_R)]       precision part: what the scalars cost
//             + [(x_E - A_E) - (x_R - A_R)]       residual: each engine's departure from its law
// Each engine's departure is judged on its own (harness/judge/own_law.hpp); the engine whose
// departure exceeds its own-law tolerance is blamed, never an engine that follows its law.
#pragma once

#include <string>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"
#include "harness/judge/own_law.hpp"

namespace dropcheck {

// One engine's run with its two laws at the run's step.
struct RunWithLaws {
  const EngineInfo& info;
  const Trajectory& run;
  const Trajectory& own;    // predict_own_arithmetic(info, scene, h)
  const Trajectory& exact;  // predict_discrete(info.law, scene, h)
};

struct Attribution {
  std::string engine, reference;
  double total = 0.0;  // max over samples and bodies of |x_E - x_R| (m)
  double final_total = 0.0;
  double final_t = 0.0;
  double law_part = 0.0;        // max |L_E - L_R|
  double precision_part = 0.0;  // max |(A_E - L_E) - (A_R - L_R)|
  double residual = 0.0;        // max |(x_E - x_R) - (A_E - A_R)|
  double budget = 0.0;         // the two own-law tolerances (positions), added (an error-controlled
                               // engine adds its measured departure from its law instead)
  std::string law_difference;  // what the two members differ in (law.hpp): "damping-order", ...
  OwnLawVerdict engine_law, reference_law;  // each engine against its own law
  std::int64_t clamped_from = -1;  // first step either engine clamped a speed; compared before it
  // Rotation, when both runs rotate: the largest geodesic angle between the two engines'
  // orientations, and between their two rotational laws' (each predicted as its own-law verdict
  // predicts it). Angles do not add like positions, but the triangle inequality bounds the runs'
  // angle by the laws' angle plus each engine's own-law residual, which the verdicts bound.
  bool rotation = false;
  double rotation_total = 0.0;     // rad
  double rotation_law_part = 0.0;  // rad
  std::string rotation_laws;       // "implicit-body/exp-map vs explicit/first-order"
  bool same_rotation_law = false;  // one member, damping in one place: the law part is zero

  // Neither engine departs from its own law (rotation included) beyond its tolerance.
  bool explained() const;
  // The two rotational laws' orientations differ by more than the two own-law angle tolerances.
  bool rotation_laws_differ() const;
  // The engines that left their own law, "ours" or "ours, bullet"; "" when none did.
  std::string blamed() const;
  // One sentence, e.g. "bullet vs ours-f64: 6.96 cm at t = 1 s (max 6.96 cm), all of it from the
  // two discrete laws (damping order); precision part 0 m; residual 3e-15 m, within rounding."
  std::string sentence() const;
};

// Both runs at the same h and recorded steps, of a scene with linear damping (`damped`: k != 0) or
// without (then where each law puts the damping is no cause).
Attribution attribute(const RunWithLaws& engine, const RunWithLaws& reference, bool damped);

}  // namespace dropcheck
