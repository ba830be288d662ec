#include "harness/core/scene.hpp"

#include <algorithm>
#include <cmath>

namespace dropcheck {

std::int64_t step_count(const Scene& scene, double h) {
  return static_cast<std::int64_t>(std::llround(scene.duration / h));
}

// dv/dt = -k*v over one step: v(t+h) = v(t)*exp(-k*h).
double decay_per_step(const Scene& scene, double h) {
  return std::exp(-scene.world.damping_rate * h);
}

double angular_decay_per_step(const Scene& scene, double h) {
  return std::exp(-scene.world.angular_damping_rate * h);
}

Vec3 box_inertia(double mass, const Vec3& h) {
  const Vec3 sq = h.cwiseProduct(h);
  return mass / 3.0 * Vec3(sq.y() + sq.z(), sq.z() + sq.x(), sq.x() + sq.y());
}

Vec3 sphere_inertia(double mass, double radius) {
  return Vec3::Constant(0.4 * mass * radius * radius);
}

Vec3 inertia_of(const Body& b) {
  if ((b.inertia.array() > 0.0).all()) return b.inertia;
  return b.shape == Shape::sphere ? sphere_inertia(b.mass, b.radius)
                                  : box_inertia(b.mass, b.half_extents);
}

Material scene_material(const Scene& scene) {
  Material m;
  for (const Body& b : scene.bodies) {
    if (b.friction) m.friction = b.friction;
    if (b.restitution) m.restitution = b.restitution;
  }
  return m;
}

bool has_spheres(const Scene& scene) {
  for (const Body& b : scene.bodies)
    if (b.shape == Shape::sphere) return true;
  return false;
}

bool pushed(const Scene& scene, std::size_t body) {
  for (const Force& f : scene.forces)
    if (std::find(f.bodies.begin(), f.bodies.end(), body) != f.bodies.end()) return true;
  return false;
}

bool needs_rotation(const Scene& scene) {
  for (const Body& b : scene.bodies)
    if (b.orientation.coeffs() != Quat::Identity().coeffs() || b.angular_velocity != Vec3::Zero())
      return true;
  for (const Torque& t : scene.torques)
    if (t.torque != Vec3::Zero()) return true;
  return false;
}

bool spins_about_z(const Scene& scene) {
  for (const Body& b : scene.bodies) {
    const Quat& q = b.orientation;
    if (q.x() != 0.0 || q.y() != 0.0 || b.angular_velocity.x() != 0.0 ||
        b.angular_velocity.y() != 0.0)
      return false;
  }
  for (const Torque& t : scene.torques)
    if (t.torque.x() != 0.0 || t.torque.y() != 0.0) return false;
  return true;
}

bool is_planar(const Scene& scene) {
  if (scene.world.gravity.z() != 0.0) return false;
  for (const Body& b : scene.bodies)
    if (b.position.z() != 0.0 || b.velocity.z() != 0.0) return false;
  for (const Force& f : scene.forces) {
    if (const auto* c = std::get_if<ConstantForce>(&f.law); c && c->force.z() != 0.0) return false;
    if (const auto* s = std::get_if<Spring>(&f.law); s && s->anchor.z() != 0.0) return false;
  }
  return true;
}

}  // namespace dropcheck
