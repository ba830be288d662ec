// The stability edge of a linear spring under each engine's discrete law.
//
// Model (per axis, y = x - x_eq): y'' = -w^2*y - gamma*y' - k*y', with w^2 = S/m, gamma = C/m (the
// spring's dashpot) and k the world damping rate. The harness evaluates the spring and dashpot
// force from the state at the START of each step (harness/core/forces.hpp), so every engine sees an
// explicit force a_n = -w^2*y_n - gamma*v_n; the world damping is the engine's own, applied as the
// per-step factor phi = exp(-k*h) where its law puts it (engine.hpp, DampingOrder):
//
//   AfterForces  (ours, Box2D, MuJoCo): v' = phi*(v + h*a);  y' = y + h*v'
//     [y' v'] = [[1 - phi*w^2*h^2, phi*h*(1 - gamma*h)], [-phi*w^2*h, phi*(1 - gamma*h)]] [y v]
//   BeforeForces (Bullet):              v' = phi*v + h*a;    y' = y + h*v'
//     [y' v'] = [[1 - w^2*h^2, h*(phi - gamma*h)], [-w^2*h, phi - gamma*h]] [y v]
//   AfterPosition (ODE):                u = v + h*a; y' = y + h*u; v' = phi*u
//     [y' v'] = [[1 - w^2*h^2, h*(1 - gamma*h)], [-phi*w^2*h, phi*(1 - gamma*h)]] [y v]
//
// With the explicit position update (y' = y + h*v, forward Euler; harness/core/law.hpp):
//   AfterForces/AfterPosition: v' = phi*(v + h*a): A = phi*w^2*h^2, beta = phi*(1 - gamma*h +
//   w^2*h^2) BeforeForces:              v' = phi*v + h*a:   A = w^2*h^2,     beta = phi - gamma*h +
//   w^2*h^2
// (trace 1 + beta - A as below): without damping beta = 1 + w^2*h^2 > 1, unstable at every h.
//
// Each matrix has determinant beta and trace 1 + beta - A, with
//   AfterForces:   A = phi*w^2*h^2,  beta = phi*(1 - gamma*h)
//   BeforeForces:  A = w^2*h^2,      beta = phi - gamma*h
//   AfterPosition: A = w^2*h^2,      beta = phi*(1 - gamma*h)
// so its characteristic polynomial is z^2 - (1 + beta - A)*z + beta = 0. Jury's test for
// z^2 + a1*z + a0 (roots in the closed unit disc, distinct on its boundary): |a0| <= 1,
// P(1) = A > 0 and P(-1) = 2*(1 + beta) - A > 0. Hence: stable iff -1 < beta <= 1 and
// A < 2*(1 + beta). Without any damping (phi = 1, gamma = 0) every law gives w*h < 2. With world
// damping only (gamma = 0): AfterForces is stable iff w*h < sqrt(2*(1 + phi)/phi) (the edge moves
// up: drag helps), the other two iff w*h < sqrt(2*(1 + phi)) (the edge moves down: drag hurts).
// phi = exp(-k*h) depends on h, so the edge is found numerically below.
//
// RK4 (Wild Magic) evaluates the spring, the dashpot and the drag at each of its four stages
// (harness/core/law.hpp, advance_rk4), so its step is the stability polynomial of the linear
// system y' = M*y, M = [[0, 1], [-w^2, -(gamma + k)]]:
//   P = I + h*M + (h*M)^2/2 + (h*M)^3/6 + (h*M)^4/24
// whose determinant and trace give beta and A = 1 + beta - trace for the same test. Undamped, the
// eigenvalues of h*M are +-i*w*h and |R(i*w*h)| <= 1 iff w*h <= 2*sqrt(2) = 2.828 (RK4's edge on
// the imaginary axis), against 2 for every semi-implicit Euler member. Stability is tested on the
// eigenvalues z = h*lambda of h*M directly, |R(z)| <= 1: det P = |R(z)|^2 is 1 - (w*h)^6/72 + ...
// undamped, whose rounding at small w*h would pass 1 by an ulp.
#include "harness/oracles/stability_theory.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <variant>

namespace dropcheck {
namespace {

struct StepCoefficients {
  double a = 0.0;     // A (see the header comment)
  double beta = 0.0;  // determinant of the step matrix
};

// RK4's P (the header comment) as beta = det P and A = 1 + beta - trace P.
StepCoefficients rk4_coefficients(const SpringModel& s, double h) {
  Eigen::Matrix2d hm;
  hm << 0.0, h, -s.omega * s.omega * h, -(s.gamma + s.k) * h;
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  const Eigen::Matrix2d p = I + hm * (I + hm / 2.0 * (I + hm / 3.0 * (I + hm / 4.0)));
  const double beta = p.determinant();
  return {1.0 + beta - p.trace(), beta};
}

// |R(z)| <= 1 (to rounding) at both eigenvalues z of h*M, lambda = (-c +- sqrt(c^2 - 4*w^2))/2.
bool rk4_spring_stable(const SpringModel& s, double h) {
  using C = std::complex<double>;
  const double c = s.gamma + s.k;
  const C root = std::sqrt(C(c * c - 4.0 * s.omega * s.omega, 0.0));
  for (const C lambda : {(-c + root) / 2.0, (-c - root) / 2.0}) {
    const C z = h * lambda;
    const C r = 1.0 + z * (1.0 + z / 2.0 * (1.0 + z / 3.0 * (1.0 + z / 4.0)));
    if (std::norm(r) > 1.0 + 8 * std::numeric_limits<double>::epsilon()) return false;
  }
  return true;
}

StepCoefficients coefficients(Law law, const SpringModel& s, double h) {
  if (law.scheme == Scheme::RK4) return rk4_coefficients(s, h);
  const double phi = std::exp(-s.k * h), wh2 = s.omega * s.omega * h * h, gh = s.gamma * h;
  if (law.position == PositionUpdate::Explicit)
    return law.damping == DampingOrder::BeforeForces
               ? StepCoefficients{wh2, phi - gh + wh2}
               : StepCoefficients{phi * wh2, phi * (1.0 - gh + wh2)};
  switch (law.damping) {
    case DampingOrder::AfterForces:
      return {phi * wh2, phi * (1.0 - gh)};
    case DampingOrder::BeforeForces:
      return {wh2, phi - gh};
    case DampingOrder::AfterPosition:
      return {wh2, phi * (1.0 - gh)};
  }
  return {};
}

}  // namespace

std::optional<SpringModel> body_spring(const Scene& scene, std::size_t index) {
  double stiffness = 0.0, dashpot = 0.0;
  for (const Force& f : scene.forces) {
    const Spring* s = std::get_if<Spring>(&f.law);
    if (!s || std::find(f.bodies.begin(), f.bodies.end(), index) == f.bodies.end()) continue;
    if (s->rest_length != 0.0) return std::nullopt;
    stiffness += s->stiffness;
    dashpot += s->damping;
  }
  if (stiffness <= 0.0) return std::nullopt;
  const double m = scene.bodies[index].mass;
  return SpringModel{std::sqrt(stiffness / m), dashpot / m, scene.world.damping_rate};
}

bool spring_step_stable(Law law, const SpringModel& spring, double h) {
  // An error-controlled integrator steps below any edge its accuracy needs: no step bound.
  if (law.scheme == Scheme::ErrorControlled) return true;
  if (law.scheme == Scheme::RK4) return rk4_spring_stable(spring, h);
  const StepCoefficients c = coefficients(law, spring, h);
  return c.beta > -1.0 && c.beta <= 1.0 && c.a < 2.0 * (1.0 + c.beta);
}

bool damping_step_stable(Law law, double k, double h) {
  return law.scheme != Scheme::RK4 || std::abs(rk4_decay(k * h)) <= 1.0;
}

std::optional<StepRotation> spring_step_rotation(Law law, const SpringModel& spring, double h) {
  // z^2 - t*z + beta = 0 with t = 1 + beta - A has the pair sqrt(beta)*exp(+-i*theta) when
  // t^2 < 4*beta, cos(theta) = t/(2*sqrt(beta)). theta is found from 1 - cos(theta) =
  // 2*sin^2(theta/2) = (2*sqrt(beta) - t)/(2*sqrt(beta)), which keeps its digits at small theta
  // where acos would not, provided 2*sqrt(beta) - t is not formed from t: t rounds near 2, and
  // the difference would keep only the bits of A above t's last one (at w*h = 1e-4 a relative
  // error of 3e-9 in theta, more than the frequency error (w*h)^2/24 = 4e-10 it carries). It is
  // A - (1 - sqrt(beta))^2, exactly A undamped: theta = 2*asin(w*h/2).
  if (law.scheme == Scheme::ErrorControlled) return std::nullopt;
  const StepCoefficients c = coefficients(law, spring, h);
  if (c.beta <= 0.0) return std::nullopt;
  const double root = std::sqrt(c.beta), gap = 1.0 - root;
  const double half_versine = (c.a - gap * gap) / (4.0 * root);  // sin^2(theta/2)
  if (!(half_versine > 0.0 && half_versine < 1.0)) return std::nullopt;
  return StepRotation{root, 2.0 * std::asin(std::sqrt(half_versine))};
}

double spring_max_stable_dt(Law law, const SpringModel& spring) {
  // Walk up from a step far inside the stable range in 1% increments to the first unstable h,
  // then bisect that bracket to double precision.
  const double rate = std::max({spring.omega, spring.gamma, spring.k, 1e-12});
  double lo = 1e-4 / rate, hi = lo;
  if (!spring_step_stable(law, spring, lo)) return 0.0;  // forward Euler on an undamped spring
  while (spring_step_stable(law, spring, hi)) {
    lo = hi;
    hi *= 1.01;
    if (hi > 1e6 / rate) return std::numeric_limits<double>::infinity();
  }
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (spring_step_stable(law, spring, mid) ? lo : hi) = mid;
  }
  return lo;
}

std::optional<double> theory_max_dt(const Scene& scene, Law law) {
  if (law.scheme == Scheme::ErrorControlled) return std::nullopt;  // no step bound (above)
  std::optional<double> edge;
  const double k = scene.world.damping_rate;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].is_static) continue;
    std::optional<double> h;
    if (std::optional<SpringModel> s = body_spring(scene, i))
      h = spring_max_stable_dt(law, *s);
    else if (law.scheme == Scheme::RK4 && k > 0.0)
      h = kRk4DampingEdge / k;
    if (h) edge = edge ? std::min(*edge, *h) : *h;
  }
  return edge;
}

}  // namespace dropcheck
