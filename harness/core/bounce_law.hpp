// How an engine's contact turns a falling body around: the members of the discrete bounce law
// (EngineInfo::bounce_law), predicted by bounce_path (harness/oracles/contact_laws.hpp) and named
// when an engine departs from the ideal member (docs/contact.md).
//
// Every engine here finds its contacts where the last step left the bodies, so a falling sphere
// meets the floor by penetrating it (or, with a speculative contact distance, just before) and the
// next step answers. With gap the distance to the floor at the start of a step (negative: depth d
// in it) and v the normal velocity then (negative: approaching), while gap < contact distance
// (or gap <= 0 for an engine whose touching pairs are contacts):
//   v_free = v - g*h                                  (this step's gravity)
//   rest   = e*(-v)  when -v > threshold, else 0      (restitution of the step-start approach)
//   gap >= 0: target = rest - gap/h                   (speculative: may close the gap this step)
//   gap <  0: push = min(erp*d/h, max_push)           (push-out of the depth)
//             target = max(push, rest), or with the push in position: target = rest and the body
//             moves h*push more (split impulse)
//   v     <- max(v_free, target)                      (the contact only pushes)
// and then x += h*v. Out of contact the sphere flies as semi-implicit Euler.
#pragma once

#include <limits>
#include <string>

namespace dropcheck {

struct BounceLaw {
  double erp = 0.0;  // error reduction: the fraction of the penetration pushed out in one step
  double max_push = std::numeric_limits<double>::infinity();  // m/s: the push-out's cap
  bool push_in_position = false;  // the push moves the body and leaves its velocity (split impulse)
  // m/s: an approach at or below this speed gets no restitution (ODE's rule; Bullet restitutes an
  // approach of exactly the threshold, an edge no shipped scene meets).
  double threshold = 0.0;
  double contact_distance = 0.0;  // m: a contact is found while the gap is below this
  // ... plus this times the smaller bounding-box half diagonal of the pair (Bullet's relative
  // contact breaking threshold).
  double contact_distance_per_size = 0.0;
  // A gap of exactly 0 (a body resting on the floor's top) is a contact too, not only an overlap
  // (ours: its contacts include touching pairs, so a resting body is held from its first step).
  bool touching = false;
};

// The ideal member: restitution of the step-start approach, no push-out, no threshold.
inline constexpr BounceLaw kIdealBounce{};

// "restitution of the step-start approach speed, push-out 0.2*depth/h capped at 0.3 m/s", the
// members set.
std::string describe(const BounceLaw& law);

// Its push-out ("push-out 0.2*depth/h capped at 0.3 m/s") and speculative contact distance
// ("speculative contact within 0.02 x the bounding half diagonal"), as describe writes them.
std::string push_text(const BounceLaw& law);
std::string contact_distance_text(const BounceLaw& law);

}  // namespace dropcheck
