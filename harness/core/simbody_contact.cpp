#include "harness/core/simbody_contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <mutex>
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

// The speed a body leaves the floor with after meeting it at `v` under gravity g, when the floor
// pushes it with `push`(depth, rate) per unit mass (before the clamp at 0): the continuous contact,
// stepped by RK4 at 1/4000 of its rest period `period` until the body is out again (0 if it never
// leaves within 100 periods).
template <class Push>
double rebound(Push push, double g, double v, double period) {
  const auto acc = [&](double depth, double rate) {  // d(rate)/dt, rate = d(depth)/dt
    return g - (depth > 0.0 ? std::max(push(depth, rate), 0.0) : 0.0);
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

// The dissipation whose continuous contact returns e*v of an impact at v, by bisection: the
// rebound falls as c grows. Hunt and Crossley's e = 1 - c*v (the start) holds for a small c*v
// only. `leaves`(c) is the rebound speed with dissipation c.
template <class Leaves>
double dissipation_for(Leaves leaves, double e, double v) {
  const double want = e * v;
  double lo = 0.0, hi = (1.0 - e) / v;
  for (int i = 0; i < 60 && hi > 0.0 && leaves(hi) > want; ++i) hi *= 2.0;
  for (int i = 0; i < 60 && hi > 0.0; ++i) {
    const double mid = 0.5 * (lo + hi);
    (leaves(mid) > want ? lo : hi) = mid;
  }
  return hi;
}

// dissipation_for once per distinct contact: the bisection steps the continuous contact some 120
// times (about 30 ms), and every load of a scene at a step asks again (a timed Simbody cell loads
// its scene up to 17 times per round). `key` holds every figure `leaves` depends on (the kind,
// stiffness, friction, transition velocity, mass, radius, g, impact speed, e and h); the answer is
// a pure function of them, so the memo changes no result.
using DissipationKey = std::array<double, 10>;

template <class Leaves>
double memoised_dissipation(const DissipationKey& key, Leaves leaves, double e, double v) {
  static std::mutex mutex;
  static std::map<DissipationKey, double> known;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (const auto it = known.find(key); it != known.end()) return it->second;
  }
  const double c = dissipation_for(leaves, e, v);
  const std::lock_guard<std::mutex> lock(mutex);
  if (known.size() >= 4096) known.clear();  // a sweep of many contacts: memory stays bounded
  return known.emplace(key, c).first->second;
}

// The first dynamic body of `shape`'s impact speed on the floor: sqrt(v_y^2 + 2*g*gap), at least
// the speed of a fall from `least` m.
double impact_speed(const Scene& scene, const Body& first, double g, double least) {
  const double bottom = first.shape == Shape::sphere ? first.radius : first.half_extents.y();
  const double gap = std::max(first.position.y() - bottom - floor_top(scene), 0.0);
  const double v = std::sqrt(first.velocity.y() * first.velocity.y() + 2.0 * g * gap);
  return std::max(v, std::sqrt(2.0 * g * least));
}

// The brick contact of the scene's boxes (the header says how each figure is chosen).
SimbodyContact brick_contact(const Scene& scene, double h, double g, double omega,
                             SimbodyContact c) {
  c.bricks = true;
  const Body* light = nullptr;
  const Body* first = nullptr;
  for (const Body& b : scene.bodies) {
    if (b.is_static || b.shape != Shape::box) continue;
    if (!first) first = &b;
    if (!light || b.mass < light->mass) light = &b;
  }
  if (!light) return c;
  c.stiffness = light->mass * omega * omega / 2.0;
  if (c.friction > 0.0) c.transition_velocity = 3.0 * kStribeckSlope * c.friction * g * h;
  const double e = scene_material(scene).restitution.value_or(0.0);
  const double v = impact_speed(scene, *first, g, first->half_extents.y());
  if (e == 0.0) {
    c.dissipation = std::min(2.0 * omega / g, 1.0 / v);
    return c;
  }
  const double m = first->mass;
  const DissipationKey key{1.0, c.stiffness, c.friction, c.transition_velocity, m, 0.0, g, v, e, h};
  c.dissipation = memoised_dissipation(
      key,
      [&](double dissipation) {
        SimbodyContact trial = c;
        trial.dissipation = dissipation;
        const auto push = [&](double depth, double rate) {
          return 4.0 * brick_vertex_force(trial, depth, rate) / m;
        };
        return rebound(push, g, v, kPeriodSteps * h);
      },
      e, v);
  return c;
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
  if (!light) return brick_contact(scene, h, g, omega, c);
  // K^(2/3) = m*omega^2/(1.5*(m*g)^(1/3)); E_pair = 3*K/(4*sqrt(R)); the pair's stiffness is
  // linear in E, so E = E_pair/pair_stiffness(1).
  const double m = light->mass;
  const double K = std::pow(m * omega * omega / (1.5 * std::cbrt(m * g)), 1.5);
  c.stiffness = 3.0 * K / (4.0 * std::sqrt(light->radius)) / pair_stiffness(1.0);
  const double v_impact = impact_speed(scene, *first, g, first->radius);
  const DissipationKey key{
      0.0,      c.stiffness, c.friction, c.transition_velocity, first->mass, first->radius, g,
      v_impact, e,           h};
  c.dissipation = memoised_dissipation(
      key,
      [&](double dissipation) {
        SimbodyContact trial = c;
        trial.dissipation = dissipation;
        const auto push = [&](double depth, double rate) {
          return hunt_crossley_force(trial, first->radius, depth, rate) / first->mass;
        };
        return rebound(push, g, v_impact, kPeriodSteps * h);
      },
      e, v_impact);
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

double brick_vertex_force(const SimbodyContact& c, double depth, double rate) {
  return 0.5 * c.stiffness * depth * (1.0 + c.dissipation * rate);
}

double stribeck(double us, double ud, double slip) {
  const auto step5 = [](double x) { return x * x * x * (10.0 + x * (6.0 * x - 15.0)); };
  if (slip >= 3.0) return ud;
  if (slip >= 1.0) return us - (us - ud) * step5((slip - 1.0) / 2.0);
  return us * step5(slip);
}

}  // namespace dropcheck
