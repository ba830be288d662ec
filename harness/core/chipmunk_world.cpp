#include "harness/core/chipmunk_world.hpp"

#include <cmath>

namespace dropcheck {

bool chipmunk_moves_along_a_line(const Scene& scene) {
  if (!scene.world.gravity.isZero(0.0) || !scene.forces.empty()) return true;
  for (const Body& b : scene.bodies)
    if (!b.is_static && !b.velocity.isZero(0.0)) return true;
  return false;
}

ChipmunkWorld chipmunk_world(const Scene& scene, bool body_materials) {
  ChipmunkWorld w;
  w.gx = scene.world.gravity.x();
  w.gy = scene.world.gravity.y();
  const bool linear = !needs_rotation(scene) || chipmunk_moves_along_a_line(scene);
  w.damping = std::exp(-(linear ? scene.world.damping_rate : scene.world.angular_damping_rate));
  // cpSpaceInit's default, cpfpow(1.0f - 0.1f, 60.0f): the difference is taken in float.
  w.collision_bias = std::pow(static_cast<double>(1.0f - 0.1f), 60.0);
  w.contacts = scene.world.contacts;
  const Material material = scene_material(scene);
  const double mu = material.friction.value_or(kChipmunkDefaultFriction);
  const double e = material.restitution.value_or(0.0);
  for (const Body& body : scene.bodies) {
    ChipmunkBox b;
    b.is_static = body.is_static;
    b.hx = body.half_extents.x();
    b.hy = body.half_extents.y();
    if (body.shape == Shape::sphere) b.radius = body.radius;
    b.x = body.position.x();
    b.y = body.position.y();
    if (!body.is_static) {
      const Quat& q = body.orientation;  // about z only (cannot_run)
      b.angle = 2.0 * std::atan2(q.z(), q.w());
      b.vx = body.velocity.x();
      b.vy = body.velocity.y();
      b.w = body.angular_velocity.z();
      b.mass = body.mass;
      b.moment = inertia_of(body).z();
    }
    // Chipmunk multiplies the two shapes' coefficients: sqrt(mu) each gives the pair mu.
    b.friction = body_materials && body.friction ? *body.friction : std::sqrt(mu);
    b.elasticity = std::sqrt(e);
    w.bodies.push_back(b);
  }
  return w;
}

}  // namespace dropcheck
