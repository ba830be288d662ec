// The continuous answer of a contact scene, where every moving body has one: what the physics says,
// beside what each engine's own law says (harness/oracles/contact_laws.hpp, stack.hpp,
// landing.hpp). Per body, by the role the contact oracles give it:
//   stack member   at its rest height throughout (a body dropped onto the column: its fall, then
//                  at rest on it, the rigid inelastic answer)
//   slide          along its slip by slide_distance_continuous with the Coulomb cone's grip mu*g
//                  (the physics, whatever pyramid an engine declares), at its height
//   bounce         falls h0 in sqrt(2*h0/g), leaves each impact at e^n times the first impact
//                  speed for a flight of 2*e^n*sqrt(2*h0/g), at rest once those flights are done
//   landing        its free flight (harness/oracles/analytic.hpp) until its bottom reaches the
//                  floor, then at rest at its rest height (a body that lands moving sideways has
//                  none: what friction does then depends on the landing)
// A body turned, or with no role, leaves the scene without one.
#pragma once

#include <optional>
#include <string>

#include "harness/core/scene.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

// Why `scene` (with contacts) has no continuous answer; empty when it has one.
std::string contact_closed_form_unavailable(const Scene& scene);

// The continuous answer sampled at every step of a run at h; nullopt when there is none.
std::optional<Trajectory> contact_closed_form(const Scene& scene, double h);

// Any scene's continuous answer: analytic_trajectory's without contacts, contact_closed_form's
// with them; and why there is none ("" when there is one).
std::optional<Trajectory> closed_form_trajectory(const Scene& scene, double h);
std::string closed_form_unavailable(const Scene& scene);

}  // namespace dropcheck
