#include "harness/core/box2d_world.hpp"

#include <cmath>
#include <numbers>

namespace dropcheck {
namespace {

Box2dBox box_of(const Body& body, float c, float c_a, float friction, float restitution) {
  Box2dBox b;
  b.is_static = body.is_static;
  b.hx = static_cast<float>(body.half_extents.x());
  b.hy = static_cast<float>(body.half_extents.y());
  b.x = static_cast<float>(body.position.x());
  b.y = static_cast<float>(body.position.y());
  if (!body.is_static) {
    const Quat& q = body.orientation;
    b.angle = static_cast<float>(2.0 * std::atan2(q.z(), q.w()));
    b.vx = static_cast<float>(body.velocity.x());
    b.vy = static_cast<float>(body.velocity.y());
    b.w = static_cast<float>(body.angular_velocity.z());
  }
  if (body.shape == Shape::sphere) {
    b.radius = static_cast<float>(body.radius);
    b.density = static_cast<float>(body.mass / (std::numbers::pi * body.radius * body.radius));
  } else {
    b.density =
        static_cast<float>(body.mass / (4.0 * body.half_extents.x() * body.half_extents.y()));
  }
  b.friction = friction;
  b.restitution = restitution;
  b.linear_damping = c;
  b.angular_damping = c_a;
  return b;
}

}  // namespace

Box2dWorld box2d_world(const Scene& scene, double h, bool body_materials) {
  Box2dWorld w;
  w.gx = static_cast<float>(scene.world.gravity.x());
  w.gy = static_cast<float>(scene.world.gravity.y());
  // dv/dt = -k*v decays by exp(-k*h) a step; Box2D's Pade step v/(1 + h*c) equals it for
  // c = expm1(k*h)/h, computed in double and rounded once to float.
  const float c = static_cast<float>(std::expm1(scene.world.damping_rate * h) / h);
  const float c_a = static_cast<float>(std::expm1(scene.world.angular_damping_rate * h) / h);
  const Material material = scene_material(scene);
  const double mu = material.friction.value_or(kBox2dDefaultFriction);
  const auto e = static_cast<float>(material.restitution.value_or(0.0));
  for (const Body& body : scene.bodies) {
    const double own = body_materials && body.friction ? *body.friction : mu;
    w.bodies.push_back(box_of(body, c, c_a, static_cast<float>(own), e));
  }
  return w;
}

}  // namespace dropcheck
