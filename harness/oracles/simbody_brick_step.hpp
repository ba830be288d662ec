// Simbody 3.7's brick contact stepped as its SemiExplicitEulerIntegrator steps it: the prediction
// of a box under the simbody adapter (harness/core/simbody_contact.hpp gives the force law and the
// adapter's choices). Read in Simbody 3.7's Simbody/src/CompliantContactSubsystem.cpp
// (calcPointHalfSpacePenaltyForce, stribeck), SimTKmath/Geometry/src/ContactTracker.cpp
// (HalfSpaceBrick::trackContact) and SimTKmath/Integrators/src/SemiExplicitEulerIntegrator.cpp.
//
// One step from the state (x, v, q, w) at its start:
//   contact   for each half-space (a static box's top face, normal n, ignoring its extent): the
//             brick's face whose outward normal is most nearly -n (it holds the deepest vertex);
//             at each of its vertices p that is x_p = n.(top - p) > 0 deep, the point c = p +
//             (x_p/2)*n moving at u = v + w x (c - x): the normal force f = (k/2)*x_p*(1 + c*r)
//             with r = -n.u (nothing when f <= 0) along n, and the friction f*mu(|u_t|) against
//             the slip u_t = u - (n.u)*n when |u_t| > Simbody's SignificantReal; the force F and
//             its moment T about the centre summed
//   velocity  v1 = v + h*(g + (F - c_d*v)/m) with the damper c_d = m*(1 - exp(-k_l*h))/h, and
//             w1 = w - h*I_w^-1*(w x I_w*w) + h*I_w^-1*(T - C_a*w) (the explicit gyroscopic term,
//             the rotational dampers C_a = I_i*(1 - exp(-k_a*h))/h per world axis)
//   position  x1 = x + h*v1, q1 = normalize(q + (h/2)*(0, w1)*q)
// in double, in an order of its own: a run and its prediction share every step but round apart.
// One difference beyond rounding: at an exact tie between two faces (a box balanced on an edge at
// 45 degrees) the replay takes the lower axis, where Simbody takes the first of the deepest
// vertex's faces in its own order (Geo::Box::getVertexFaces); no shipped scene meets one.
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/simbody_contact.hpp"

namespace dropcheck {

// The force and the moment about its centre that the half-space with normal `normal` through
// `top` exerts on a brick of `half_extents` at `position`, turned by `orientation`, moving at
// `velocity` and `angular_velocity` (world frame), under contact `c`.
struct Wrench {
  Vec3 force = Vec3::Zero();
  Vec3 moment = Vec3::Zero();
};
Wrench brick_half_space(const SimbodyContact& c, const Vec3& half_extents, const Vec3& position,
                        const Quat& orientation, const Vec3& velocity, const Vec3& angular_velocity,
                        const Vec3& normal, const Vec3& top);

// Body `body` (a box) of `scene` after steps 0..steps at step h under the adapter's brick contact:
// its position and velocity, and its rotation in `turns` when given. Throws std::invalid_argument
// when the body is no box or a force of the scene pushes it.
std::vector<BodyState> simbody_brick_states(const Scene& scene, std::size_t body, double h,
                                            std::int64_t steps,
                                            std::vector<RotationState>* turns = nullptr);

}  // namespace dropcheck
