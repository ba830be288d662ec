// The phase drift of a law on an undamped linear spring over a long run, and the error against the
// closed form that drift predicts: why the convergence sweep of a long run is pre-asymptotic while
// its engine follows its law (harness/study/checks.cpp, "convergence to analytic").
//
// Per axis about the equilibrium (y = x - x_eq, W = v0/omega), the closed form is
//   y(t) = Re[(Y0 - i*W) * exp(i*omega*t)].
// Every semi-implicit member of the law family with no damping has the step matrix
// [[1 - (w*h)^2, h], [-w^2*h, 1]] (harness/oracles/stability_theory.cpp), eigenvalues
// exp(+-i*theta) with theta = 2*asin(omega*h/2), and from y_0 = Y0, y_1 = Y0*(1 - (w*h)^2) + h*v0:
//   y_n = Re[(Y0 - i*b) * exp(i*n*theta)],  b = (W - Y0*omega*h/2)/c,  c = sqrt(1 - (omega*h/2)^2).
// With phi_n = n*(theta - omega*h) = omega*r*t_n (r = theta/(omega*h) - 1, the relative frequency
// error) the error at t_n = n*h is
//   y_n - y(t_n) = Re[exp(i*omega*t_n) * ((Y0 - i*W)*(exp(i*phi_n) - 1) + dC*exp(i*phi_n))],
//   dC = -i*(b - W)   (the law's constant first-order part: its initial phase offset omega*h/2).
// |Re[exp(i*a)*Z]| <= the larger singular value of [Re Z, Im Z], so over the run
//   max |error| <= P + D,  P = 2*S*sin(min(drift, pi)/2),  D = |b - W|,
// S the semi-major axis of the orbit (larger singular value of [Y0, W]) and drift = omega*r*T.
// And one oscillation near the envelope's peak (the run's end, or where the drift passes pi) has a
// sample within theta/2 of the orbit's major axis, so
//   max |error| >= 2*S*sin(max(min(drift, pi) - 2*pi*r, 0)/2)*cos(theta/2) - D.
// P is second order in h times T; D is first order: while P is not small against D the error is
// the drift, not the first-order term, and the observed order is not 1.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "harness/core/law.hpp"
#include "harness/core/scene.hpp"

namespace dropcheck {

// The drift of one body on an undamped spring at one step h, and the error band it predicts.
struct DriftPrediction {
  std::string body;
  double h = 0.0;           // s
  double omega = 0.0;       // rad/s
  double theta = 0.0;       // rad turned per step by the law (from its eigenvalues)
  double relative = 0.0;    // r = theta/(omega*h) - 1
  double duration = 0.0;    // T: the time of the run's last step (s)
  double drift = 0.0;       // omega*r*T (rad)
  double semi_axis = 0.0;   // S (m)
  double drift_part = 0.0;  // P = 2*S*sin(min(drift, pi)/2) (m)
  double offset = 0.0;      // D = |b - W|, the law's first-order part (m)
  double lower = 0.0;       // lower bound of the worst error over the run (m)
  double upper = 0.0;       // upper bound of the worst error over the run (m)
};

// For each dynamic body on an undamped linear spring (rest length 0, no dashpot, no world damping)
// whose law at h turns it by a pair of unit modulus, over at least one period: its prediction.
// Empty for every other scene or law (explicit Euler grows on an undamped spring: not a rotation).
std::vector<DriftPrediction> predict_drift(const Scene& scene, Law law, double h);

// The order a sweep shows where a first-order error D*(h/h0) meets a second-order drift P*(h/h0)^2
// leaves the first-order band (tolerance::kFirstOrderHigh) once P/D exceeds this at the coarser
// step: (1 + q)/(1 + q/2) = 2^(kFirstOrderHigh - 1), q = 0.155.
double drift_significant_ratio();

// One step of a sweep against the drift's band.
struct DriftBand {
  double h = 0.0;       // s
  double drift = 0.0;   // the largest drift of any body at h (rad)
  double lower = 0.0;   // the band of the worst error over bodies: the largest lower bound (m)
  double upper = 0.0;   // ... and the largest upper bound (m)
  double error = 0.0;   // the measured error (m)
  bool within = false;  // error within [lower, upper], widened by the noise
};

// Whether the phase drift explains a convergence sweep (errors e, m, at steps h, largest first).
struct DriftVerdict {
  bool applies = false;    // a body drifts, and its drift part is significant at the coarser step
                           // of the sweep's last pair (P >= drift_significant_ratio() * D)
  bool explained = false;  // applies, and every error lies in its band (+- noise)
  Law law;                 // the law judged
  std::string body;        // the body that drifts most at the coarsest step
  double duration = 0.0;   // T: the time of the run's last step (s)
  double omega = 0.0;      // that body's angular frequency (rad/s)
  std::vector<DriftBand> steps;  // when it applies: one per step of the sweep, largest first

  // Where the drift omega*T*(omega*h)^2/24 falls to the law's phase offset omega*h/2:
  // 12/(omega^2*T) (s); well below it the error is first order.
  double first_order_edge() const;
  // When it applies: the drift, the predicted band and the measured error, one sentence.
  std::string sentence() const;
  // When explained: the cause, one sentence (the check's LIMIT).
  std::string limit_text() const;
};

// Judges the errors of a sweep of `scene` under `law` against the drift prediction; `noise` (m)
// widens each band for the engine's rounding.
DriftVerdict judge_drift(const Scene& scene, Law law, std::span<const double> h,
                         std::span<const double> e, double noise);

}  // namespace dropcheck
