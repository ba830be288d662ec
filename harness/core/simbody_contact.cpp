#include "harness/core/simbody_contact.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace dropcheck {
namespace {

// The floor's top: the highest top face of a static box, or -inf.
double floor_top(const Scene& scene) {
  double top = -INFINITY;
  for (const Body& b : scene.bodies)
    if (b.is_static && b.shape == Shape::box)
      top = std::max(top, b.position.y() + b.half_extents.y());
  return top;
}

}  // namespace

SimbodyContact simbody_contact(const Scene& scene, double h) {
  SimbodyContact c;
  const double g = std::max(scene.world.gravity.norm(), 1e-3);
  const double omega = 2.0 * std::numbers::pi / (kPeriodSteps * h);
  const double e = scene_material(scene).restitution.value_or(0.0);
  c.friction = scene_material(scene).friction.value_or(0.0);
  const Body* light = nullptr;
  const Body* first = nullptr;
  for (const Body& b : scene.bodies) {
    if (b.is_static || b.shape != Shape::sphere) continue;
    if (!first) first = &b;
    if (!light || b.mass < light->mass) light = &b;
  }
  if (!light) return c;
  // K^(2/3) = m*omega^2/(1.5*(m*g)^(1/3)); E_pair = 3*K/(4*sqrt(R)); E = 2^(3/2)*E_pair.
  const double m = light->mass;
  const double K = std::pow(m * omega * omega / (1.5 * std::cbrt(m * g)), 1.5);
  c.stiffness = std::pow(2.0, 1.5) * 3.0 * K / (4.0 * std::sqrt(light->radius));
  const double gap = std::max(first->position.y() - first->radius - floor_top(scene), 0.0);
  const double v_first = std::sqrt(first->velocity.y() * first->velocity.y() + 2.0 * g * gap);
  const double v_impact = std::max(v_first, std::sqrt(2.0 * g * first->radius));
  c.dissipation = (1.0 - e) / v_impact;
  return c;
}

double hunt_crossley_force(const SimbodyContact& c, double radius, double depth, double rate) {
  const double e23 = std::cbrt(c.stiffness * c.stiffness);  // E^(2/3) of each surface
  const double s1 = e23 / (e23 + e23);
  const double pair = std::pow(s1 * e23, 1.5);
  const double dissipation = c.dissipation * s1 + c.dissipation * (1 - s1);
  const double k = (4.0 / 3.0) * std::sqrt(radius) * pair;
  return k * depth * std::sqrt(depth) * (1 + 1.5 * dissipation * rate);
}

}  // namespace dropcheck
