// Unbounded growth: energy or speed beyond what the physics allows, per kind of body.
#include "harness/judge/stability_growth.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

#include "harness/core/forces.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/rotation_metrics.hpp"
#include "harness/oracles/landing.hpp"
#include "harness/oracles/stack.hpp"

namespace dropcheck::stability_detail {
namespace {

// Peak of f(s) over the samples whose step lies in [from, to].
template <typename F>
double window_max(const Trajectory& run, std::int64_t from, std::int64_t to, F f) {
  double m = 0.0;
  for (std::size_t s = 0; s < run.samples(); ++s)
    if (run.recorded[s] >= from && run.recorded[s] <= to) m = std::max(m, f(s));
  return m;
}

// Spring body. Oscillation energy about the equilibrium x_eq = A + m*a/S (gravity and constant
// forces are absorbed by x_eq):  E = 1/2 m |v|^2 + 1/2 S |x - x_eq|^2. Along the exact solution
// dE/dt = -(C + m*k)*|v|^2 <= 0, so E(t) <= E(0). Semi-implicit Euler conserves a nearby
// quadratic form instead, whose ellipse flattens as w*h -> 2: from rest, E swings up to
// E(0)/(1 - w*h/2) on a stable run (measured: 16.0x at w*h = 1.875, 100x at 1.98, 1000x at 1.998),
// so a bound on E alone would put the edge below 2/w. The bound is therefore only a backstop for
// runs too short to judge (energy_factor), and the test is in time: an unstable step multiplies E
// every step, so the peak of the last third of the run exceeds that of the first third by
// growth_factor (measured over 60 steps: 13x at w*h = 2.0001, 8.8e6x at 2.01; stable runs 0.9994x
// to 1.0008x once the thirds are longer than the beat of the discrete oscillation, ~50 steps at
// w*h = 1.999).
void spring_growth(const Scene& scene, const Trajectory& run, std::size_t i, const BodyLaw& law,
                   const ClassifyOptions& o, std::vector<Failure>& out) {
  const double m = scene.bodies[i].mass, S = law.stiffness;
  const Vec3 eq = law.anchor + m * law.accel / S;
  auto energy = [&](std::size_t s) {
    const BodyState& st = run.at(s, i);
    return 0.5 * m * st.velocity.squaredNorm() + 0.5 * S * (st.position - eq).squaredNorm();
  };
  // A start at rest at x_eq has E(0) = 0: measure against 1e-6 of the equilibrium's distance from
  // the origin, the scale of float rounding of the position.
  const double e_ref = std::max(energy(0), 0.5 * S * std::pow(1e-6 * std::max(1.0, eq.norm()), 2));
  const std::int64_t last = run.recorded.back();
  const double early = window_max(run, 0, last / 3, energy);
  const double late = window_max(run, last - last / 3, last, energy);
  const bool windows = run.samples() >= 9 && late > o.growth_factor * std::max(early, e_ref);
  const double limit = windows ? o.growth_factor * std::max(early, e_ref) : o.energy_factor * e_ref;
  for (std::size_t s = 0; s < run.samples(); ++s) {
    if (energy(s) <= limit) continue;
    const double w = std::sqrt(S / m);
    out.push_back(
        {FailureMode::unbounded_growth, run.body_names[i], run.recorded[s],
         printf_string("body '%s': oscillation energy 1/2 m v^2 + 1/2 S |x - x_eq|^2 grew from "
                       "%.3g J to %.3g J (x%.3g) by step %lld%s (omega*h = %.4g)",
                       run.body_names[i].c_str(), energy(0), energy(s), energy(s) / e_ref,
                       static_cast<long long>(run.recorded[s]),
                       windows ? printf_string(", %.3g x the peak of the run's first third",
                                               energy(s) / std::max(early, e_ref))
                                     .c_str()
                               : "",
                       w * run.h)});
    return;
  }
}

// Free flight: v' = a - k*v. Exactly, v(t) = a/k + (v0 - a/k)*exp(-k*t) is a convex combination of
// v0 and the terminal velocity a/k, so |v(t)| <= max(|v0|, |a|/k); for k = 0, |v(t)| <= |v0| +
// |a|*t. The discrete laws move the terminal speed: |a|*h*phi/(1 - phi) when damping follows the
// forces, |a|*h/(1 - phi) when it precedes them (Bullet), = (|a|/k)*kh/(1 - exp(-kh)) >= |a|/k;
// each step is again a convex combination of v and that terminal velocity, so no first-order law
// exceeds max(|v0|, (|a|/k)*kh/(1 - exp(-kh))) (k = 0: v_n = v0 + n*a*h exactly, the same bound).
void speed_growth(const Scene& scene, const Trajectory& run, std::size_t i, const BodyLaw& law,
                  const ClassifyOptions& o, std::vector<Failure>& out) {
  const double k = scene.world.damping_rate, a = law.accel.norm(), h = run.h;
  const double v0 = scene.bodies[i].velocity.norm();
  const double terminal = k > 0.0 ? (a / k) * (k * h / -std::expm1(-k * h)) : 0.0;
  for (std::size_t s = 0; s < run.samples(); ++s) {
    const double t = run.time(s);
    const double bound = k > 0.0 ? std::max(v0, terminal) : v0 + a * t;
    if (std::isnan(bound))
      return;  // |v0| or |a| overflowed: no bound to claim (NaN/Inf is its own mode)
    const double v = run.at(s, i).velocity.norm();
    if (v <= bound * (1.0 + o.speed_slack) + 1e-12) continue;
    out.push_back(
        {FailureMode::unbounded_growth, run.body_names[i], run.recorded[s],
         printf_string("body '%s': speed %.4g m/s at step %lld exceeds %.4g m/s, the most this "
                       "free flight reaches under any first-order damping order (%s)",
                       run.body_names[i].c_str(), v, static_cast<long long>(run.recorded[s]), bound,
                       k > 0.0 ? "max(|v0|, (|a|/k)*kh/(1 - exp(-kh)))" : "|v0| + |a|*t")});
    return;
  }
}

// Energy stored in one spring acting on a body at `x`: 1/2 s (|x - anchor| - L)^2.
double spring_energy(const Spring& s, const Vec3& x) {
  const double stretch = (x - s.anchor).norm() - s.rest_length;
  return 0.5 * s.stiffness * stretch * stretch;
}

// Contact scene: total mechanical energy E = sum over dynamic bodies of 1/2 m|v|^2 - m*a.x plus the
// springs' energy. Contacts, drag and dashpots only remove energy (a tunnelling body keeps E);
// first-order steps and penetration recovery add a little. Growth: E(t) - E(0) above contact_gain
// times the peak total kinetic energy, i.e. most of the motion is energy the physics never
// supplied; and above the lift an engine's contacts may give resting bodies: resting_lift per
// contact level under each (sum of m*|a|*resting_lift*level). Without that floor a resting stack,
// whose kinetic energy is ~0, fails on Box2D's 0.015 m skins (0.073 J by step 1, 0.44 J once
// rested) or Bullet's 2.2e-5 J of solver residual.
void contact_growth(const Scene& scene, const Trajectory& run, const ClassifyOptions& o,
                    std::vector<Failure>& out) {
  std::vector<BodyLaw> laws;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) laws.push_back(body_law(scene, i));
  auto energies = [&](std::size_t s, double& kinetic) {
    double total = 0.0;
    kinetic = 0.0;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      if (scene.bodies[i].is_static) continue;
      const BodyState& st = run.at(s, i);
      const double m = scene.bodies[i].mass, ke = 0.5 * m * st.velocity.squaredNorm();
      kinetic += ke;
      total += ke - m * laws[i].accel.dot(st.position);
    }
    for (const Force& f : scene.forces)
      if (const Spring* sp = std::get_if<Spring>(&f.law))
        for (std::size_t i : f.bodies) total += spring_energy(*sp, run.at(s, i).position);
    return total;
  };
  // Each body may rise resting_lift per contact level under it: its stack level, 1 for a body on
  // its own, and every dynamic body's count for one stacked outside a judged stack (at worst the
  // top of a column of all of them).
  int dynamic = 0;
  for (const Body& b : scene.bodies) dynamic += b.is_static ? 0 : 1;
  std::vector<int> level(scene.bodies.size(), 1);
  for (const LandingExclusion& x : landing_exclusions(scene)) level[x.body] = dynamic;
  for (const StackSetup& st : stack_setups(scene))
    for (const StackLevel& l : st.levels) level[l.body] = l.level;
  double ke = 0.0, peak_ke = 0.0, lift = 0.0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (!scene.bodies[i].is_static)
      lift += scene.bodies[i].mass * laws[i].accel.norm() * o.resting_lift * level[i];
  const double e0 = energies(0, ke);
  for (std::size_t s = 0; s < run.samples(); ++s) energies(s, ke), peak_ke = std::max(peak_ke, ke);
  for (std::size_t s = 0; s < run.samples(); ++s) {
    const double gain = energies(s, ke) - e0;
    if (gain <= o.contact_gain * peak_ke + lift || gain <= 1e-9) continue;
    out.push_back(
        {FailureMode::unbounded_growth, "", run.recorded[s],
         printf_string("the bodies' mechanical energy rose by %.3g J by step %lld, more than "
                       "%.2g x their peak kinetic energy %.3g J: contacts added energy",
                       gain, static_cast<long long>(run.recorded[s]), o.contact_gain, peak_ke)});
    return;
  }
}

// A turning body in free flight: its world angular momentum changes only by the torques, so
// |L(t)| <= |L0| + |tau|*t, and a body of smallest principal moment I_min with momentum |L| has at
// most |L|^2/(2*I_min) of rotational energy. A run whose rotational energy w.L/2 passes that bound
// (with the speed slack) is growing without physics: an explicit gyroscopic term at a step too
// large for the spin (its energy gain per step grows with |w|*h) does it.
void rotational_growth(const Scene& scene, const Trajectory& run, std::size_t i,
                       const ClassifyOptions& o, std::vector<Failure>& out) {
  const Body& b = scene.bodies[i];
  const Vec3 I = inertia_of(b);
  std::vector<Vec3> torques(scene.bodies.size());
  compute_torques(scene, torques);
  const Vec3 L0 = world_momentum(b.orientation, b.angular_velocity, I);
  for (std::size_t s = 0; s < run.samples(); ++s) {
    const RotationState& r = run.rotation_at(s, i);
    const Vec3 L = world_momentum(r.orientation, r.angular_velocity, I);
    const double energy = 0.5 * r.angular_velocity.dot(L);
    const double momentum = L0.norm() + torques[i].norm() * run.time(s);
    const double bound = momentum * momentum / (2.0 * I.minCoeff());
    if (energy <= bound * (1.0 + o.speed_slack) + 1e-12) continue;
    out.push_back(
        {FailureMode::unbounded_growth, run.body_names[i], run.recorded[s],
         printf_string("body '%s': rotational energy %.4g J at step %lld exceeds %.4g J, the most "
                       "a body of smallest moment %.4g kg m^2 holds with angular momentum %.4g "
                       "kg m^2/s (|L0| + |tau|*t): the rotation grows without physics (|w|*h = "
                       "%.3g)",
                       run.body_names[i].c_str(), energy, static_cast<long long>(run.recorded[s]),
                       bound, I.minCoeff(), momentum, r.angular_velocity.norm() * run.h)});
    return;
  }
}

}  // namespace

void find_growth(const Scene& scene, const Trajectory& run, const ClassifyOptions& o,
                 std::vector<Failure>& out) {
  if (scene.world.contacts) return contact_growth(scene, run, o, out);
  if (run.rotates)
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
      if (!scene.bodies[i].is_static) rotational_growth(scene, run, i, o, out);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].is_static) continue;
    const BodyLaw law = body_law(scene, i);
    if (law.nonlinear) continue;  // no quadratic energy to bound: a spring with a rest length
    if (law.stiffness > 0.0)
      spring_growth(scene, run, i, law, o, out);
    else
      speed_growth(scene, run, i, law, o, out);
  }
}

}  // namespace dropcheck::stability_detail
