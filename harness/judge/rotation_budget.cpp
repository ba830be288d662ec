#include "harness/judge/rotation_budget.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "harness/core/forces.hpp"
#include "harness/core/rotation_metrics.hpp"
#include "harness/oracles/free_rotation.hpp"

namespace dropcheck {
namespace {

// The body-frame angular velocity R^T*w.
Vec3 body_omega(const RotationState& r) {
  return r.orientation.conjugate() * r.angular_velocity;
}

double linear_energy(const Scene& scene, const Body& b, const BodyState& s) {
  return 0.5 * b.mass * s.velocity.squaredNorm() - b.mass * scene.world.gravity.dot(s.position);
}

// The axis (0, 1, 2) of the middle principal moment.
int intermediate_axis(const Vec3& I) {
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int a, int b) { return I[a] < I[b]; });
  return order[1];
}

bool torque_free(const Scene& scene, std::size_t body) {
  std::vector<Vec3> torques(scene.bodies.size());
  compute_torques(scene, torques);
  return torques[body] == Vec3::Zero() && !scene.world.contacts;
}

// Angular damping dw/dt = ... - k*w in closed form: with w(t) = exp(-k*t)*u(tau(t)) and
// tau = (1 - exp(-k*t))/k, Euler's equations with the damping term become the undamped ones for
// u in tau (I*w' = (I*w) x w - k*I*w turns into I*du/dtau = (I*u) x u). So the damped body is the
// free body on a slowed clock, shrunk by exp(-k*t); tau = t without damping.
double free_time(double k, double t) {
  return k == 0.0 ? t : -std::expm1(-k * t) / k;
}

// The inverse: the time t at which the free clock reads tau (tau < 1/k).
double real_time(double k, double tau) {
  return k == 0.0 ? tau : -std::log1p(-k * tau) / k;
}

}  // namespace

RotationBudget rotation_budget(const Scene& scene, const Trajectory& run, std::size_t body) {
  RotationBudget out;
  const Body& b = scene.bodies[body];
  const Vec3 I = inertia_of(b);
  std::vector<Vec3> L;
  for (std::size_t s = 0; s < run.samples(); ++s) {
    const RotationState& r = run.rotation_at(s, body);
    L.push_back(world_momentum(r.orientation, r.angular_velocity, I));
  }
  out.momentum_drift = momentum_drift(L);
  const auto rotational = [&](std::size_t s) {
    return 0.5 * run.rotation_at(s, body).angular_velocity.dot(L[s]);
  };
  const std::size_t last = run.samples() - 1;
  out.rotational_energy = rotational(0);
  out.rotational_energy_change = rotational(last) - rotational(0);
  out.linear_energy_change =
      linear_energy(scene, b, run.at(last, body)) - linear_energy(scene, b, run.at(0, body));
  out.closed_form = torque_free(scene, body);
  std::optional<FreeRotation> closed;
  try {
    if (out.closed_form) closed.emplace(I, body_omega(run.rotation_at(0, body)));
  } catch (const std::invalid_argument&) {
    out.closed_form = false;  // moments on the triangle inequality's edge within rounding
  }
  if (!out.closed_form) {
    out.closed_form_error = NAN;
    return out;
  }
  const FreeRotation& exact = *closed;
  const double k = scene.world.angular_damping_rate;
  const int axis = intermediate_axis(I);
  for (std::size_t s = 0; s < run.samples(); ++s) {
    const Vec3 w = body_omega(run.rotation_at(s, body));
    const double t = run.time(s);
    const Vec3 closed = std::exp(-k * t) * exact.omega(free_time(k, t));
    out.closed_form_error = std::max(out.closed_form_error, (w - closed).norm());
    if (s == 0) continue;
    const double a = body_omega(run.rotation_at(s - 1, body))[axis], c = w[axis];
    if ((a < 0.0) != (c < 0.0) && a != 0.0)
      out.flips.push_back(run.time(s - 1) + (run.time(s) - run.time(s - 1)) * a / (a - c));
  }
  for (double tau : exact.flips(free_time(k, run.time(last))))
    out.closed_form_flips.push_back(real_time(k, tau));
  return out;
}

}  // namespace dropcheck
