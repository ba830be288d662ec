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
//   rest   = e*(-v)  when -v > threshold, else 0      (restitution of the step-start approach;
//            of -v_free for an engine that takes its approach after the step's gravity; the
//            threshold compared with e times that approach for one that thresholds the
//            rebound; at most max_rebound)
//   gap >= 0: target = rest - gap/h                   (speculative: may close the gap this step)
//   gap <  0: push = min(erp*d/h, max_push)           (push-out of the depth)
//             target = max(push, rest), or with the push in position: target = rest and the body
//             moves h*push more (split impulse)
//   v     <- max(v_free, (cfm*v_free + target)/(1 + cfm))
//            (the contact only pushes; a regularised row, solved against (1 + cfm) times its
//            diagonal entry, stops 1/(1 + cfm) of the way from v_free to its target)
// and then x += h*v (x += h*v_free for a contact resolved after the position update, a neighbour no
// engine declares). Out of contact the sphere flies as semi-implicit Euler.
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
  // Restitution of the approach after this step's gravity, -v_free (DART: its LCP's relative
  // velocity is read after the unconstrained velocity update), not of the step-start approach.
  bool free_approach = false;
  // The threshold holds the rebound e*approach, not the approach (DART's bouncing threshold).
  bool threshold_on_rebound = false;
  double max_rebound = std::numeric_limits<double>::infinity();  // m/s: the restitution's cap
  double cfm = 0.0;  // constraint force mixing relative to the contact row's diagonal entry
  // The position moves with v_free before the contact is resolved (a neighbour `check` names; no
  // engine declares it): the contact changes the velocity and not the step's position.
  bool resolved_after_position = false;
};

// The ideal member: restitution of the step-start approach, no push-out, no threshold.
inline constexpr BounceLaw kIdealBounce{};

// "restitution of the step-start approach speed, push-out 0.2*depth/h capped at 0.3 m/s", the
// members set.
std::string describe(const BounceLaw& law);

// Its restitution rule ("restitution of the step-start approach speed above 0.1 m/s"), push-out
// ("push-out 0.2*depth/h capped at 0.3 m/s"), speculative contact distance ("speculative contact
// within 0.02 x the bounding half diagonal") and regularisation ("constraint force mixing 1e-05 of
// the row's diagonal entry"), as describe writes them.
std::string restitution_text(const BounceLaw& law);
std::string push_text(const BounceLaw& law);
std::string contact_distance_text(const BounceLaw& law);
std::string cfm_text(const BounceLaw& law);

}  // namespace dropcheck
