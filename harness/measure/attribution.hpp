// Attribution: why two engines' trajectories of one free-flight scene differ.
//
// Write x_E, x_R for the two engines' positions and L_E, L_R for their exact discrete laws
// (harness/oracles/discrete_law.hpp) at the same step. Then, sample by sample,
//   x_E - x_R = (L_E - L_R)  +  [(x_E - L_E) - (x_R - L_R)]
//               law part        residual: each engine's departure from its own law
// The law part is the scheme difference (damping order: O(h), vanishes as h -> 0). The residual is
// rounding when it stays within the two scalars' rounding budget; beyond it, it is unexplained and
// deserves a person's attention (an adapter bug, a hidden default, a clamp).
#pragma once

#include <string>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

// Rounding budget for an engine's departure from its own law over a scene (m): f32 1e-4, f64 1e-9.
// The floor of the bounds the conformance checks use (measured worst on the shipped scenes at the
// default step: f32 2.0e-5 m, f64 2.0e-14 m).
double rounding_budget(Scalar scalar);

// The budget for a run that follows `law`: the floor above, or the worst case of rounding the
// position to the scalar once per step (half an ulp, eps/2 * |x|) accumulated over n steps,
// n * eps/2 * max|x|, whichever is larger. Long runs far from the origin earn a larger budget
// (seed_part3 in f32 at h = 1/240: 720 steps, |x| <= 12.3 m: 5.3e-4 m; measured 1.4e-4 m).
double rounding_budget(Scalar scalar, const Trajectory& law);

struct Attribution {
  std::string engine, reference;
  double total = 0.0;     // max over samples and bodies of |x_E - x_R| (m)
  double final_total = 0.0;
  double final_t = 0.0;
  double law_part = 0.0;  // max |L_E - L_R|
  double residual = 0.0;  // max |(x_E - x_R) - (L_E - L_R)|
  double budget = 0.0;    // rounding_budget(E, L_E) + rounding_budget(R, L_R)
  bool explained() const { return residual <= budget; }

  // One sentence, e.g. "bullet vs ours-f64: 6.96 cm at t = 1 s (max 6.96 cm), all of it from the
  // two discrete laws (damping order); residual 3e-15 m, within f64 rounding."
  std::string sentence() const;
};

// Both trajectories at the same h and recorded steps, with their engines' laws.
Attribution attribute(const Trajectory& engine, const Trajectory& engine_law, Scalar engine_scalar,
                      const Trajectory& reference, const Trajectory& reference_law,
                      Scalar reference_scalar);

// A length in readable units: "6.96 cm", "3.1e-15 m", "0 m".
std::string format_length(double metres);

}  // namespace dropcheck
