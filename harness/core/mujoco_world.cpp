#include "harness/core/mujoco_world.hpp"

#include <cmath>
#include <numbers>
#include <optional>

namespace dropcheck {

MujocoSoftContact restitution_solref(double e, double h) {
  const double log_e = std::log(e);  // -inf at e = 0: zeta = 1
  const double zeta =
      e > 0.0 ? -log_e / std::sqrt(std::numbers::pi * std::numbers::pi + log_e * log_e) : 1.0;
  const double w0 = 1.0 / (2.0 * h);
  return {.solref = {-(w0 * w0), -(2.0 * zeta * w0)}};
}

MujocoWorld mujoco_world(const Scene& scene, double h, bool body_materials) {
  MujocoWorld w;
  w.h = h;
  w.gravity = scene.world.gravity;
  w.contacts = scene.world.contacts;
  const std::optional<double> e = scene_material(scene).restitution;
  w.contact = e ? restitution_solref(*e, h) : MujocoSoftContact{.solref = {2.0 * h, 1.0}};
  const double mu = scene_material(scene).friction.value_or(kMujocoDefaultFriction);
  // (exp(k*h) - 1)/h per unit mass (per unit moment for the rotational dofs).
  const double c = std::expm1(scene.world.damping_rate * h) / h;
  const double c_a = std::expm1(scene.world.angular_damping_rate * h) / h;
  for (const Body& b : scene.bodies) {
    MujocoBody m;
    m.name = b.name;
    m.is_static = b.is_static;
    m.half_extents = b.half_extents;
    if (b.shape == Shape::sphere) m.radius = b.radius;
    m.position = b.position;
    m.orientation = b.orientation;
    m.friction = body_materials && b.friction ? *b.friction : mu;
    if (!b.is_static) {
      m.velocity = b.velocity;
      m.angular_velocity_body = b.orientation.conjugate() * b.angular_velocity;
      m.mass = b.mass;
      m.inertia = inertia_of(b);
      m.damping = b.mass * c;
      m.angular_damping = m.inertia * c_a;
    }
    w.bodies.push_back(m);
  }
  return w;
}

}  // namespace dropcheck
