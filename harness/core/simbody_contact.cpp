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

// The speed a sphere of `radius` and `mass` leaves the floor with after meeting it at `v`, under
// contact `c` and gravity g: the continuous contact, stepped by RK4 at 1/4000 of its rest period
// `period` until the sphere is out again (0 if it never leaves within 100 periods).
double rebound(const SimbodyContact& c, double radius, double mass, double g, double v,
               double period) {
  const auto acc = [&](double depth, double rate) {  // d(rate)/dt, rate = d(depth)/dt
    const double f = depth > 0.0 ? std::max(hunt_crossley_force(c, radius, depth, rate), 0.0) : 0.0;
    return g - f / mass;
  };
  const double dt = period / 4000.0;
  double d = 0.0, r = v;
  for (int n = 0; n < 400000; ++n) {
    const double k1d = r, k1r = acc(d, r);
    const double k2d = r + dt / 2 * k1r, k2r = acc(d + dt / 2 * k1d, r + dt / 2 * k1r);
    const double k3d = r + dt / 2 * k2r, k3r = acc(d + dt / 2 * k2d, r + dt / 2 * k2r);
    const double k4d = r + dt * k3r, k4r = acc(d + dt * k3d, r + dt * k3r);
    const double d_next = d + dt / 6 * (k1d + 2 * k2d + 2 * k3d + k4d);
    const double r_next = r + dt / 6 * (k1r + 2 * k2r + 2 * k3r + k4r);
    if (d_next < 0.0) return -(r + (r_next - r) * (d / (d - d_next)));  // out: interpolated
    d = d_next, r = r_next;
  }
  return 0.0;
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
  // K^(2/3) = m*omega^2/(1.5*(m*g)^(1/3)); E_pair = 3*K/(4*sqrt(R)); the pair's stiffness is
  // linear in E, so E = E_pair/pair_stiffness(1).
  const double m = light->mass;
  const double K = std::pow(m * omega * omega / (1.5 * std::cbrt(m * g)), 1.5);
  c.stiffness = 3.0 * K / (4.0 * std::sqrt(light->radius)) / pair_stiffness(1.0);
  const double gap = std::max(first->position.y() - first->radius - floor_top(scene), 0.0);
  const double v_first = std::sqrt(first->velocity.y() * first->velocity.y() + 2.0 * g * gap);
  const double v_impact = std::max(v_first, std::sqrt(2.0 * g * first->radius));
  // The dissipation whose continuous contact returns e*v_impact, by bisection: the rebound falls
  // as c grows. Hunt and Crossley's e = 1 - c*v (the start) holds for a small c*v only.
  const double period = kPeriodSteps * h;
  const auto leaves = [&](double dissipation) {
    SimbodyContact trial = c;
    trial.dissipation = dissipation;
    return rebound(trial, first->radius, first->mass, g, v_impact, period);
  };
  const double want = e * v_impact;
  double lo = 0.0, hi = (1.0 - e) / v_impact;
  for (int i = 0; i < 60 && hi > 0.0 && leaves(hi) > want; ++i) hi *= 2.0;
  for (int i = 0; i < 60 && hi > 0.0; ++i) {
    const double mid = 0.5 * (lo + hi);
    (leaves(mid) > want ? lo : hi) = mid;
  }
  c.dissipation = hi;
  return c;
}

double pair_stiffness(double E) {
  const double e23 = std::cbrt(E * E);  // E^(2/3) of each surface
  const double s1 = e23 / (e23 + e23);
  return std::pow(s1 * e23, 1.5);
}

double hunt_crossley_force(const SimbodyContact& c, double radius, double depth, double rate) {
  // Both surfaces share c: the pair's c1*s1 + c2*(1 - s1) is c.
  const double k = (4.0 / 3.0) * std::sqrt(radius) * pair_stiffness(c.stiffness);
  return k * depth * std::sqrt(depth) * (1 + 1.5 * c.dissipation * rate);
}

}  // namespace dropcheck
