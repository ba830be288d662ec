#include "harness/oracles/analytic.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

namespace dropcheck {
namespace {

struct Linear {
  Vec3 accel = Vec3::Zero();   // a = g + F/m (constant part)
  double stiffness = 0.0;      // S (N/m)
  Vec3 anchor = Vec3::Zero();  // A (weighted by stiffness)
  double dashpot = 0.0;        // C (N*s/m)
};

Linear combine(const Scene& scene, std::size_t index) {
  const Body& b = scene.bodies[index];
  Linear l;
  Vec3 weighted = Vec3::Zero();
  l.accel = scene.world.gravity;
  for (const Force& f : scene.forces) {
    bool acts = false;
    for (std::size_t i : f.bodies) acts = acts || i == index;
    if (!acts) continue;
    if (const auto* c = std::get_if<ConstantForce>(&f.law)) {
      l.accel += c->force / b.mass;
    } else {
      const Spring& s = std::get<Spring>(f.law);
      l.stiffness += s.stiffness;
      weighted += s.stiffness * s.anchor;
      l.dashpot += s.damping;
    }
  }
  if (l.stiffness > 0.0) l.anchor = weighted / l.stiffness;
  return l;
}

// (u - (1 - exp(-u)))/u^2 = 1/2 - u/6 + u^2/24 - ... = sum_n (-u)^n/(n+2)!, for u = k*t >= 0.
// Below u = 0.5 it is summed as the series (terms < 1e-19 after 18); the direct form cancels
// catastrophically for small u (it put x off by 3.8e-7 m at k = 1e-9, 0.57 m at k = 1e-15).
double phi2(double u) {
  if (u >= 0.5) return (u + std::expm1(-u)) / (u * u);
  double term = 0.5, sum = 0.0;
  for (int n = 0; n < 18; ++n) {
    sum += term;
    term *= -u / (n + 3);
  }
  return sum;
}

// x'' = a - k*x':  v(t) = a/k + (v0 - a/k)*exp(-k*t)
//                  x(t) = x0 + (a/k)*t + (v0 - a/k)*(1 - exp(-k*t))/k
// Written with E = 1 - exp(-k*t) = -expm1(-k*t) as x = x0 + v0*E/k + a*t^2*phi2(k*t),
// v = v0*(1 - E) + a*E/k, accurate for every k >= 0; k = 0 is the parabola, exactly.
BodyState drag_flight(const Body& b, const Vec3& a, double k, double t) {
  if (k == 0.0) return {b.position + b.velocity * t + 0.5 * a * t * t, b.velocity + a * t};
  const double u = k * t, e_over_k = -std::expm1(-u) / k;
  const Vec3 x = b.position + b.velocity * e_over_k + a * (t * t * phi2(u));
  const Vec3 v = b.velocity * std::exp(-u) + a * e_over_k;
  return {x, v};
}

// y'' + 2*zeta*w*y' + w^2*y = 0, y = x - x_eq, per axis with y0, y0'. With p = zeta*w:
//   under-damped (p < w, wd = sqrt(w^2 - p^2)): y = exp(-p t)*(y0*cos(wd t) + (y0' +
//   p*y0)/wd*sin(wd t)) critical     (p = w):                       y = exp(-p t)*(y0 + (y0' +
//   p*y0)*t) over-damped  (p > w, r1,2 = -p -+ sqrt(p^2 - w^2)): y = c1*exp(r1 t) + c2*exp(r2 t)
// (tests/harness/oracles/analytic_test.cpp checks each against the ODE by finite differences.)
void oscillator_axis(double y0, double v0, double w, double p, double t, double& y, double& v) {
  const double e = std::exp(-p * t);
  if (p < w) {
    const double wd = std::sqrt(w * w - p * p), c = std::cos(wd * t), s = std::sin(wd * t);
    const double b = (v0 + p * y0) / wd;
    y = e * (y0 * c + b * s);
    v = e * ((b * wd - p * y0) * c - (y0 * wd + p * b) * s);
  } else if (p == w) {
    const double b = v0 + p * y0;
    y = e * (y0 + b * t);
    v = e * (b - p * (y0 + b * t));
  } else {
    const double q = std::sqrt(p * p - w * w), r1 = -p + q, r2 = -p - q;
    const double c1 = (v0 - r2 * y0) / (r1 - r2), c2 = y0 - c1;
    y = c1 * std::exp(r1 * t) + c2 * std::exp(r2 * t);
    v = c1 * r1 * std::exp(r1 * t) + c2 * r2 * std::exp(r2 * t);
  }
}

BodyState spring_flight(const Body& b, const Linear& l, double k, double t) {
  const double w = std::sqrt(l.stiffness / b.mass);
  const double p = 0.5 * (l.dashpot / b.mass + k);
  const Vec3 eq = l.anchor + l.accel * b.mass / l.stiffness;  // x_eq = A + (m*g + F)/S
  BodyState s;
  for (int i = 0; i < 3; ++i) {
    double y = 0.0, v = 0.0;
    oscillator_axis(b.position[i] - eq[i], b.velocity[i], w, p, t, y, v);
    s.position[i] = eq[i] + y;
    s.velocity[i] = v;
  }
  return s;
}

}  // namespace

std::string analytic_unavailable(const Scene& scene) {
  if (scene.world.contacts) return "contacts (see the landing oracle)";
  if (needs_rotation(scene))
    return "the body turns: its translation has a closed form, its rotation is judged against "
           "each engine's rotational law";
  for (const Force& f : scene.forces)
    if (const auto* s = std::get_if<Spring>(&f.law); s && s->rest_length != 0.0)
      return "spring with a rest length (nonlinear)";
  return {};
}

BodyState analytic_state(const Scene& scene, std::size_t index, double t) {
  const Body& b = scene.bodies[index];
  if (b.is_static) return {b.position, Vec3::Zero()};
  const Linear l = combine(scene, index);
  const double k = scene.world.damping_rate;
  return l.stiffness > 0.0 ? spring_flight(b, l, k, t) : drag_flight(b, l.accel, k, t);
}

Trajectory sampled_answer(const Scene& scene, double h, std::int64_t every, const char* engine,
                          const std::function<BodyState(std::size_t, double)>& state) {
  Trajectory t;
  t.engine = engine;
  t.scene = scene.name;
  t.h = h;
  t.steps = step_count(scene, h);
  for (const Body& b : scene.bodies) t.body_names.push_back(b.name);
  every = std::max<std::int64_t>(every, 1);
  for (std::int64_t n = 0; n <= t.steps; ++n) {
    if (n % every != 0 && n != t.steps) continue;
    t.recorded.push_back(n);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
      t.states.push_back(state(i, static_cast<double>(n) * h));
  }
  return t;
}

std::optional<Trajectory> analytic_trajectory(const Scene& scene, double h,
                                              const RunOptions& options) {
  if (!analytic_unavailable(scene).empty()) return std::nullopt;
  return sampled_answer(scene, h, options.record_every, "analytic",
                        [&scene](std::size_t i, double t) { return analytic_state(scene, i, t); });
}

}  // namespace dropcheck
