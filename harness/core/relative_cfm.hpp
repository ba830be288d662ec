// Constraint force mixing relative to each diagonal entry (DART's contact): every row of the
// step's LCP solves against (1 + cfm)*A_ii instead of A_ii, and a depth d is pushed out at erp*d/h,
// at most max_push. What that does to a box resting, sliding or landing flat on a static floor, per
// step, with v_free the box's normal velocity (up positive) after the step's gravity and damping
// and d its depth at the step's start (a contact while d >= 0):
//   v_n' = max(v_free, (cfm*v_free + min(erp*d/h, max_push))/(1 + cfm)),   d' = d - h*v_n'
// (the regularised normal row stops 1/(1 + cfm) of the approach and adds the push-out). Resting,
// v_free = v_n - g*h: the box sinks towards cfm*g*h^2/erp, by a factor close to (1 - erp) a step.
// Landing from a height, it stops about |v|*h deep and climbs out at the cap, less cfm*g*h. Its
// normal impulse per unit mass, v_n' - v_free, bounds the friction of the step (mu times it, per
// pyramid axis); a tangential row inside its bounds stops 1/(1 + cfm) of the slip and leaves
// cfm/(1 + cfm) of it.
#pragma once

#include <limits>
#include <string>

namespace dropcheck {

struct RelativeCfm {
  double cfm = 0.0;  // 0: none (the contact law is rigid)
  double erp = 0.0;  // fraction of the depth pushed out per step
  double max_push = std::numeric_limits<double>::infinity();  // m/s: the push-out's cap
};

// The floor contact's normal state after one step of `law` (see above).
struct NormalState {
  double v = 0.0;  // m/s, up positive
  double d = 0.0;  // m, depth (positive: sunk)
};
// Steps `s` once in contact, from the free velocity v_free; returns the normal impulse per unit
// mass (m/s): -v_free for a rigid law, which cancels the approach.
double contact_step(const RelativeCfm& law, double v_free, double h, NormalState& s);

// contact_step under gravity g into the floor and no damping: v_free = v_n - g*h.
double normal_step(const RelativeCfm& law, double g, double h, NormalState& s);

// The depth the box tends to: cfm*g*h^2/erp (0 for a rigid law).
double steady_sink(const RelativeCfm& law, double g, double h);

// "constraint force mixing 1e-05 of each diagonal entry, error reduction 0.01, push-out capped at
// 0.001 m/s" or "none".
std::string describe(const RelativeCfm& law);

}  // namespace dropcheck
