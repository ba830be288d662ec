// What the chipmunk adapter (adapters/chipmunk.cpp) builds from a scene, as Chipmunk's own
// parameters: declared once, for the adapter that creates the space and for the replay of
// Chipmunk's step that predicts it (harness/oracles/chipmunk_step.hpp).
//
//   gravity             cpSpaceSetGravity (x, y); planar scenes only
//   damping             cpSpaceSetDamping(exp(-k)): the fraction kept per second, one value for v
//                       and w (exp(-k_a) when nothing moves along a line)
//   body                cpBodyNew(m, I_z) with the scene's mass and moment about z, or
//                       cpBodyNewStatic; cpBodySetPosition, cpBodySetVelocity, cpBodySetAngle
//                       (2*atan2(q_z, q_w)), cpBodySetAngularVelocity
//   box (contacts)      cpBoxShapeNew(body, 2*hx, 2*hy, 0): no rounding radius, no mass of its own
//   sphere (contacts)   cpCircleShapeNew(body, r, (0, 0)), no mass of its own
//   friction            sqrt(mu) on every shape (0.5 unset): Chipmunk multiplies the two
//   elasticity          sqrt(e) on every shape (0 unset): Chipmunk multiplies the two
//   solver              cpSpaceSetIterations 10 (Chipmunk's default); collision slop 0.005 m (the
//                       default 0.1 is for pixels: a tenth of a unit cube); collision bias and
//                       persistence Chipmunk's defaults, (1 - 0.1)^60 and 3 steps
// Bodies are added in the scene's order, each body's shape right after it.
#pragma once

#include <vector>

#include "harness/core/scene.hpp"

namespace dropcheck {

struct ChipmunkBox {
  bool is_static = false;
  double hx = 0.0, hy = 0.0;
  double radius = 0.0;  // > 0: a circle of this radius at the body's origin instead of a box
  double x = 0.0, y = 0.0, angle = 0.0;
  double vx = 0.0, vy = 0.0, w = 0.0;
  double mass = 0.0, moment = 0.0;  // dynamic bodies only
  double friction = 0.0;            // the shape's u
  double elasticity = 0.0;          // the shape's e
};

struct ChipmunkWorld {
  double gx = 0.0, gy = 0.0;
  double damping = 1.0;  // per second
  int iterations = 10;
  double collision_slop = 0.005;       // m
  double collision_bias = 0.0;         // chipmunk_world: cpSpaceInit's cpfpow(1 - 0.1, 60)
  unsigned collision_persistence = 3;  // steps
  bool contacts = false;               // the boxes get shapes
  std::vector<ChipmunkBox> bodies;     // in the scene's order
};

// The pair friction when the scene sets none.
inline constexpr double kChipmunkDefaultFriction = 0.5;

// True when some body moves along a line (a start velocity, gravity, or a force): the space's one
// damping is then the linear rate's.
bool chipmunk_moves_along_a_line(const Scene& scene);

// `scene` as the adapter builds it. With `body_materials` (identify --combine) each shape carries
// its body's own friction where it sets one, so that Chipmunk's product makes each pair's value.
ChipmunkWorld chipmunk_world(const Scene& scene, bool body_materials = false);

}  // namespace dropcheck
