// One step of the mean-corner contact law (harness/core/turned_contact.hpp) from a recorded state,
// in long double: what an engine declaring it must reach one step later.
//
// A contact decision within rounding of its threshold may go either way: a corner whose height
// over the face is within `decide` of 0 may be in contact or not in the engine's arithmetic. Each
// such corner doubles the candidates; every combination is one candidate next state, and a run
// follows the law at that step when one of them matches it.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/scene.hpp"

namespace dropcheck {

// What the law needs of the scene and the engine, fixed over a run.
struct TurnedContactSetup {
  const Scene* scene = nullptr;
  Law linear;            // the engine's linear member: v = phi*(v + g*h) needs AfterForces
  RotationLaw rotation;  // its rotational member (G and Q)
  double h = 0.0;
  double phi = 1.0, phi_a = 1.0;             // per-step linear and angular damping factors
  double friction = 0.0, restitution = 0.0;  // the scene's mu and e (0 unset)
};

// The setup of `scene` for an engine with these members at h, or why the law does not apply: a
// dynamic body that is not a box, two dynamic bodies (a turned box collides only with static
// boxes), a static body that is not a box, forces or torques, or damping not after the forces.
struct TurnedContactScope {
  TurnedContactSetup setup;
  std::string not_judged;  // empty when the law applies
};
TurnedContactScope turned_contact_scope(const Scene& scene, const EngineInfo& info, double h);

// One candidate of the law's next state: every body's, laid out like a trajectory's sample.
struct TurnedCandidate {
  std::vector<BodyState> linear;
  std::vector<RotationState> rotation;
  int contacts = 0;  // corners in contact (all static boxes together)
};

// The candidates one step after the state `linear`, `rotation` (one per body), with corners within
// `decide` (m) of the face tried both ways (at most 2^12 candidates; beyond, the nearer side).
std::vector<TurnedCandidate> turned_contact_step(const TurnedContactSetup& setup,
                                                 std::span<const BodyState> linear,
                                                 std::span<const RotationState> rotation,
                                                 double decide);

}  // namespace dropcheck
