// How an engine's contact turns a falling body around: the members of the discrete bounce law
// (EngineInfo::bounce_law), predicted by bounce_path (harness/oracles/contact_laws.hpp) and named
// when an engine departs from the ideal member (docs/contact.md).
//
// Every engine here finds its contacts where the last step left the bodies, so a falling sphere
// meets the floor by penetrating it and the next step answers. With d > 0 the penetration at the
// start of a step and v the normal velocity then (negative: approaching):
//   v_free = v - g*h                                  (this step's gravity)
//   target = min(erp*d/h, max_push)                   (push-out of the penetration)
//   target = max(target, e*(-v))  when -v > threshold (restitution of the step-start approach)
//   v     <- max(v_free, target)                      (the contact only pushes)
// and then x += h*v. Out of contact the sphere flies as semi-implicit Euler.
#pragma once

#include <limits>
#include <string>

namespace dropcheck {

struct BounceLaw {
  double erp = 0.0;  // error reduction: the fraction of the penetration pushed out in one step
  double max_push = std::numeric_limits<double>::infinity();  // m/s: the push-out's cap
  double threshold = 0.0;  // m/s: an approach at or below this speed gets no restitution
};

// The ideal member: restitution of the step-start approach, no push-out, no threshold.
inline constexpr BounceLaw kIdealBounce{};

// "restitution of the step-start speed, push-out min(0.2*depth/h, 0.3 m/s)", the members set.
std::string describe(const BounceLaw& law);

}  // namespace dropcheck
