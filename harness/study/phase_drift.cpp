#include "harness/study/phase_drift.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "harness/core/number_format.hpp"
#include "harness/judge/own_law.hpp"
#include "harness/judge/stability_classify.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/oracles/stability_theory.hpp"
#include "harness/study/sweep.hpp"

namespace dropcheck {
namespace {

constexpr double kPi = std::numbers::pi;

// The larger singular value of the 3x2 matrix [a, b]: the semi-major axis of the orbit
// Re[(a - i*b)*exp(i*t)], from the larger eigenvalue of its Gram matrix.
double semi_major(const Vec3& a, const Vec3& b) {
  const double p = a.squaredNorm(), q = b.squaredNorm(), s = a.dot(b);
  return std::sqrt(0.5 * (p + q) + std::hypot(0.5 * (p - q), s));
}

// The prediction for body i at step h (the derivation is in the header).
std::optional<DriftPrediction> predict_body(const Scene& scene, Law law, std::size_t i, double h) {
  const std::optional<SpringModel> s = body_spring(scene, i);
  if (!s || s->gamma != 0.0 || s->k != 0.0 || law.position != PositionUpdate::SemiImplicit)
    return std::nullopt;
  const std::optional<StepRotation> turn = spring_step_rotation(law, *s, h);
  if (!turn || turn->rho != 1.0) return std::nullopt;
  DriftPrediction p;
  p.body = scene.bodies[i].name;
  p.h = h;
  p.omega = s->omega;
  p.theta = turn->theta;
  p.relative = turn->theta / (s->omega * h) - 1.0;
  p.duration = static_cast<double>(step_count(scene, h)) * h;
  if (p.duration < 2.0 * kPi / s->omega) return std::nullopt;  // less than one oscillation
  p.drift = s->omega * p.relative * p.duration;
  // The orbit about the equilibrium x_eq = A + m*a/S (gravity and constant forces move it).
  const Body& body = scene.bodies[i];
  const stability_detail::BodyLaw f = stability_detail::body_law(scene, i);
  const Vec3 y0 = body.position - (f.anchor + body.mass * f.accel / f.stiffness);
  const Vec3 w = body.velocity / s->omega;
  const double wh = s->omega * h, c = std::sqrt(1.0 - 0.25 * wh * wh);
  p.semi_axis = semi_major(y0, w);
  p.offset = ((w - 0.5 * wh * y0) / c - w).norm();
  const double peak = std::min(p.drift, kPi);
  p.drift_part = 2.0 * p.semi_axis * std::sin(0.5 * peak);
  p.upper = p.drift_part + p.offset;
  const double before = std::max(peak - 2.0 * kPi * p.relative, 0.0);
  p.lower = std::max(
      2.0 * p.semi_axis * std::sin(0.5 * before) * std::cos(0.5 * p.theta) - p.offset, 0.0);
  return p;
}

// "1.5, 1.45, 0.487 m": four significant digits each.
std::string list(std::span<const double> v, const char* unit) {
  std::string out;
  for (double x : v) out += (out.empty() ? "" : ", ") + sig(x, 4);
  return out + unit;
}

// "1/60, 1/120, 1/240".
std::string steps_text(std::span<const double> h) {
  std::string out;
  for (double x : h) out += (out.empty() ? "" : ", ") + step_text(x);
  return out;
}

}  // namespace

std::vector<DriftPrediction> predict_drift(const Scene& scene, Law law, double h) {
  std::vector<DriftPrediction> out;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (!scene.bodies[i].is_static)
      if (std::optional<DriftPrediction> p = predict_body(scene, law, i, h)) out.push_back(*p);
  return out;
}

double drift_significant_ratio() {
  const double g = std::exp2(tolerance::kFirstOrderHigh - 1.0);
  return (g - 1.0) / (1.0 - 0.5 * g);
}

DriftVerdict judge_drift(const Scene& scene, Law law, std::span<const double> h,
                         std::span<const double> e, double noise) {
  DriftVerdict v;
  if (h.size() < 2 || h.size() != e.size()) return v;
  // The band of the worst error over bodies: the largest lower and upper bound of any drifting
  // body (a body the drift does not cover must stay below the upper bound, or it is unexplained).
  std::vector<double> lower, upper, drift;
  const DriftPrediction* worst = nullptr;  // the body that drifts most, at the coarsest step
  std::vector<std::vector<DriftPrediction>> all;
  for (double step : h) {
    all.push_back(predict_drift(scene, law, step));
    if (all.back().empty()) return v;
    double lo = 0.0, hi = 0.0, most = 0.0;
    for (const DriftPrediction& p : all.back()) {
      lo = std::max(lo, p.lower), hi = std::max(hi, p.upper), most = std::max(most, p.drift);
    }
    lower.push_back(lo), upper.push_back(hi), drift.push_back(most);
  }
  for (const DriftPrediction& p : all.front())
    if (!worst || p.drift > worst->drift) worst = &p;
  // Significant at the coarser step of the last pair: the drift alone bends that order out of band.
  const std::size_t coarser = h.size() - 2;
  for (const DriftPrediction& p : all[coarser])
    v.applies = v.applies || p.drift_part >= drift_significant_ratio() * p.offset;
  if (!v.applies) return v;
  v.explained = true;
  std::string outside;
  for (std::size_t k = 0; k < h.size(); ++k)
    if (e[k] < lower[k] - noise || e[k] > upper[k] + noise) {
      v.explained = false;
      outside += (outside.empty() ? "" : ", ") + step_text(h[k]);
    }
  std::string bands;
  for (std::size_t k = 0; k < h.size(); ++k)
    bands += (k ? ", " : "") + ("[" + sig(lower[k], 4) + ", " + sig(upper[k], 4) + "]");
  const double t = worst->duration;
  v.text = "phase drift of its law (" + law_family_name(law) + ") over " + sig(t, 4) + " s on '" +
           worst->body + "', omega*T*(theta/(omega*h) - 1) with theta the angle of the law's " +
           "eigenvalues: " + list(drift, " rad") + " at h = " + steps_text(h) +
           "; 2*S*sin(drift/2) +- D (S the orbit's semi-major axis, D the law's first-order " +
           "initial phase offset) bounds its error against the closed form to " + bands +
           " m; measured " + list(e, " m") +
           (v.explained ? ": within the band"
                        : ": OUTSIDE the band at h = " + outside + ", not explained by the drift");
  if (!v.explained) return v;
  // The first-order regime: where the drift omega*T*(omega*h)^2/24 falls to the law's phase offset
  // omega*h/2, h = 12/(omega^2*T); well below it the error is C*h.
  const double w = worst->omega, edge = 12.0 / (w * w * t);
  const std::size_t last = h.size() - 1;
  v.limit = "pre-asymptotic: the phase drift of semi-implicit Euler over " + sig(t, 4) + " s on '" +
            worst->body + "' is " + sig(drift.front(), 3) + " rad at h = " + step_text(h.front()) +
            " and still " + sig(drift.back(), 3) + " rad at h = " + step_text(h.back()) +
            " (error predicted " + sig(lower.front(), 4) + ".." + sig(upper.front(), 4) +
            " m and " + sig(lower[last], 4) + ".." + sig(upper[last], 4) + " m, measured " +
            sig(e.front(), 4) + " m and " + sig(e[last], 4) +
            " m): the error is that drift, second order in h, until h is well below "
            "12/(omega^2*T) = " +
            sig(edge, 3) + " s (" + sig(t / edge, 3) + " steps)";
  return v;
}

}  // namespace dropcheck
