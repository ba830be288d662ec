// What the box2d adapter (adapters/box2d.cpp) builds from a scene, as Box2D's own float
// parameters: declared once, for the adapter that creates the bodies and for the replay of Box2D's
// step that predicts them (harness/oracles/box2d_step.hpp).
//
//   position, velocity  x and y of the scene's (z dropped: planar scenes only)
//   angle               2*atan2(q_z, q_w) (turns about z only)
//   box                 b2PolygonShape::SetAsBox(hx, hy), density m/(4*hx*hy): the scene's mass
//                       per unit depth over the square's area
//   sphere              b2CircleShape of the radius, density m/(pi*r^2)
//   damping             c = (exp(k*h) - 1)/h, so that Box2D's v/(1 + h*c) is exp(-k*h)
//   friction            the scene's mu on every fixture (0.5 unset): Box2D mixes sqrt(f1*f2)
//   restitution         the scene's e on every fixture (0 unset): Box2D takes the larger of the
//                       two, so every pair gets e; restitutionThreshold Box2D's default 1 m/s
#pragma once

#include <vector>

#include "harness/core/scene.hpp"

namespace dropcheck {

// One body: a b2BodyDef and, with contacts, one fixture holding a SetAsBox(hx, hy) polygon, or a
// circle of `radius` when it is positive.
struct Box2dBox {
  bool is_static = false;
  float hx = 0.0f, hy = 0.0f;
  float radius = 0.0f;  // > 0: a b2CircleShape (m_radius) at the body's origin instead of a box
  float x = 0.0f, y = 0.0f, angle = 0.0f;
  float vx = 0.0f, vy = 0.0f, w = 0.0f;
  float density = 0.0f;
  float friction = 0.2f;
  float restitution = 0.0f;
  float linear_damping = 0.0f, angular_damping = 0.0f;
};

struct Box2dWorld {
  float gx = 0.0f, gy = 0.0f;
  std::vector<Box2dBox> bodies;  // in the scene's order, the order Box2D creates them
};

// The fixture friction when the scene sets none.
inline constexpr float kBox2dDefaultFriction = 0.5f;

// `scene` at step h. With `body_materials` (identify --combine) each fixture carries its body's own
// friction where it sets one, so that Box2D's mix, not the mapping, makes each pair's value.
Box2dWorld box2d_world(const Scene& scene, double h, bool body_materials = false);

}  // namespace dropcheck
