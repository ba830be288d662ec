#include "harness/core/forces.hpp"

#include <variant>

namespace dropcheck {

// Spring with dashpot to a fixed anchor (scene.hpp): F = -s*(|d| - L)*d/|d| - c*v, d = x - anchor.
Vec3 spring_force(const Spring& s, const BodyState& state) {
  const Vec3 d = state.position - s.anchor;
  Vec3 f = -s.damping * state.velocity;
  if (s.rest_length == 0.0) return f - s.stiffness * d;
  const double len = d.norm();
  if (len > 0.0) f -= s.stiffness * (len - s.rest_length) * (d / len);
  return f;
}

std::vector<std::vector<const Spring*>> springs_by_body(const Scene& scene) {
  std::vector<std::vector<const Spring*>> out(scene.bodies.size());
  for (const Force& force : scene.forces)
    if (const auto* s = std::get_if<Spring>(&force.law))
      for (std::size_t i : force.bodies)
        if (!scene.bodies[i].is_static) out[i].push_back(s);
  return out;
}

Vec3 stage_force(const Vec3& start_force, std::span<const Spring* const> springs,
                 const BodyState& start, const BodyState& now) {
  Vec3 f = start_force;
  for (const Spring* s : springs) f += spring_force(*s, now) - spring_force(*s, start);
  return f;
}

void compute_forces(const Scene& scene, std::span<const BodyState> states, std::span<Vec3> out) {
  for (Vec3& f : out) f.setZero();
  for (const Force& force : scene.forces) {
    for (std::size_t i : force.bodies) {
      if (scene.bodies[i].is_static) continue;
      if (const auto* c = std::get_if<ConstantForce>(&force.law))
        out[i] += c->force;
      else
        out[i] += spring_force(std::get<Spring>(force.law), states[i]);
    }
  }
}

void compute_torques(const Scene& scene, std::span<Vec3> out) {
  for (Vec3& t : out) t.setZero();
  for (const Torque& torque : scene.torques)
    for (std::size_t i : torque.bodies)
      if (!scene.bodies[i].is_static) out[i] += torque.torque;
}

}  // namespace dropcheck
