// Constraint force mixing relative to each diagonal entry (DART's contact): every row of the
// step's LCP solves against (1 + cfm)*A_ii instead of A_ii, and a depth d is pushed out at erp*d/h.
// What that does to a box resting or sliding on a static floor, per step, with g the gravity into
// the floor, v_n the box's normal velocity (up positive) and d its depth:
//   v_n' = (cfm*(v_n - g*h) + erp*d/h)/(1 + cfm),   d' = d - h*v_n'
// (the regularised normal row stops 1/(1 + cfm) of the approach and adds the push-out), so the box
// sinks towards cfm*g*h^2/erp, by a factor close to (1 - erp) a step. Its normal impulse per unit
// mass, v_n' - (v_n - g*h), bounds the friction of the step (mu times it, per pyramid axis); a
// tangential row inside its bounds stops 1/(1 + cfm) of the slip and leaves cfm/(1 + cfm) of it.
#pragma once

#include <string>

namespace dropcheck {

struct RelativeCfm {
  double cfm = 0.0;  // 0: none (the contact law is rigid)
  double erp = 0.0;  // fraction of the depth pushed out per step
};

// The floor contact's normal state after one step of `law` (see above).
struct NormalState {
  double v = 0.0;  // m/s, up positive
  double d = 0.0;  // m, depth (positive: sunk)
};
// Steps `s` once under gravity g into the floor at step h; returns the normal impulse per unit
// mass (m/s): g*h for a rigid law.
double normal_step(const RelativeCfm& law, double g, double h, NormalState& s);

// The depth the box tends to: cfm*g*h^2/erp (0 for a rigid law).
double steady_sink(const RelativeCfm& law, double g, double h);

// "constraint force mixing 1e-05 of each diagonal entry, error reduction 0.01" or "none".
std::string describe(const RelativeCfm& law);

}  // namespace dropcheck
