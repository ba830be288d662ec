// The stability edge of a linear spring under each engine's discrete law (stability_theory.cpp):
// the theory the stability study compares its measured edge with.
#pragma once

#include <optional>

#include "harness/core/law.hpp"
#include "harness/core/scene.hpp"

namespace dropcheck {

// A linear spring on one body as the stability analysis sees it: w^2 = S/m, gamma = C/m, k drag.
struct SpringModel {
  double omega = 0.0;  // rad/s
  double gamma = 0.0;  // dashpot per unit mass, 1/s
  double k = 0.0;      // world damping rate, 1/s
};

// The linear springs (rest length 0) acting on body `index`, combined; nullopt if none or if one of
// them has a rest length (nonlinear: no single w).
std::optional<SpringModel> body_spring(const Scene& scene, std::size_t index);

// True when one step of `law` with spring force from the start-of-step state is stable at h
// (derivation in stability_theory.cpp).
bool spring_step_stable(Law law, const SpringModel& spring, double h);

// True when one step of `law` keeps a velocity damped at rate k from growing at h: always for the
// Euler members (phi = exp(-k*h) < 1); for RK4 while |R(k*h)| <= 1, i.e. k*h <= kRk4DampingEdge.
bool damping_step_stable(Law law, double k, double h);

// The root of R(u) = 1 above u = 0 (R in harness/core/law.hpp): RK4's largest stable k*h on free
// flight. R(u) - 1 = u*(-1 + u/2 - u^2/6 + u^3/24); the cubic's one real root.
inline constexpr double kRk4DampingEdge = 2.7852935634;

// One step of a law on a spring as a rotation: its eigenvalues rho*exp(+-i*theta).
struct StepRotation {
  double rho = 0.0;    // modulus: the amplitude factor per step (1 for an undamped spring)
  double theta = 0.0;  // angle: the phase the discrete oscillation turns per step (rad)
};

// The complex eigenvalue pair of one step of `law` on `spring` at h; nullopt when the eigenvalues
// are real (no oscillation: overdamped, or beyond the edge).
std::optional<StepRotation> spring_step_rotation(Law law, const SpringModel& spring, double h);

// The largest h at which `law` is stable for `spring` (the first edge above h = 0); 0 when it is
// unstable from the smallest step tried, 1e-4/max(omega, gamma, k), on: an explicit position update
// on an undamped spring (forward Euler) is unstable at every h.
double spring_max_stable_dt(Law law, const SpringModel& spring);

// The theoretical edge of `scene` under `law`: the smallest over its dynamic bodies of the edge of
// each body's linear springs (rest_length 0) and, for RK4 under world damping k, of the drag alone
// (kRk4DampingEdge/k); nullopt when nothing bounds the step (free flight under an Euler member).
std::optional<double> theory_max_dt(const Scene& scene, Law law);

}  // namespace dropcheck
