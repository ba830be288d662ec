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

namespace {

// The band of the worst error over the bodies that drift at h: the largest lower and upper bound
// of any body (a body the drift does not cover must stay below the upper bound, or it is
// unexplained), and the largest drift.
DriftBand band_at(const std::vector<DriftPrediction>& bodies, double h, double error,
                  double noise) {
  DriftBand b{h, 0.0, 0.0, 0.0, error, false};
  for (const DriftPrediction& p : bodies) {
    b.lower = std::max(b.lower, p.lower), b.upper = std::max(b.upper, p.upper),
    b.drift = std::max(b.drift, p.drift);
  }
  b.within = !(error < b.lower - noise || error > b.upper + noise);
  return b;
}

// The body that drifts most.
const DriftPrediction& most_drifting(const std::vector<DriftPrediction>& bodies) {
  const DriftPrediction* worst = nullptr;
  for (const DriftPrediction& p : bodies)
    if (!worst || p.drift > worst->drift) worst = &p;
  return *worst;
}

}  // namespace

DriftVerdict judge_drift(const Scene& scene, Law law, std::span<const double> h,
                         std::span<const double> e, double noise) {
  DriftVerdict v;
  if (h.size() < 2 || h.size() != e.size()) return v;
  std::vector<std::vector<DriftPrediction>> all;
  for (double step : h) {
    all.push_back(predict_drift(scene, law, step));
    if (all.back().empty()) return v;
  }
  // Significant at the coarser step of the last pair: the drift alone bends that order out of band.
  for (const DriftPrediction& p : all[h.size() - 2])
    v.applies = v.applies || p.drift_part >= drift_significant_ratio() * p.offset;
  if (!v.applies) return v;
  const DriftPrediction& worst = most_drifting(all.front());
  v.law = law, v.body = worst.body, v.duration = worst.duration, v.omega = worst.omega;
  v.explained = true;
  for (std::size_t k = 0; k < h.size(); ++k) {
    v.steps.push_back(band_at(all[k], h[k], e[k], noise));
    v.explained = v.explained && v.steps.back().within;
  }
  return v;
}

double DriftVerdict::first_order_edge() const {
  return 12.0 / (omega * omega * duration);
}

std::string DriftVerdict::sentence() const {
  if (!applies) return "";
  std::vector<double> h, drift, e;
  std::string bands, outside;
  for (const DriftBand& b : steps) {
    h.push_back(b.h), drift.push_back(b.drift), e.push_back(b.error);
    bands += (bands.empty() ? "[" : ", [") + sig(b.lower, 4) + ", " + sig(b.upper, 4) + "]";
    if (!b.within) outside += (outside.empty() ? "" : ", ") + step_text(b.h);
  }
  return "phase drift of its law (" + law_family_name(law) + ") over " + sig(duration, 4) +
         " s on '" + body + "', omega*T*(theta/(omega*h) - 1) with theta the angle of the law's " +
         "eigenvalues: " + list(drift, " rad") + " at h = " + steps_text(h) +
         "; 2*S*sin(drift/2) +- D (S the orbit's semi-major axis, D the law's first-order " +
         "initial phase offset) bounds its error against the closed form to " + bands +
         " m; measured " + list(e, " m") +
         (explained ? ": within the band"
                    : ": OUTSIDE the band at h = " + outside + ", not explained by the drift");
}

std::string DriftVerdict::limit_text() const {
  if (!explained) return "";
  const DriftBand &first = steps.front(), &last = steps.back();
  const double edge = first_order_edge();
  return "pre-asymptotic: the phase drift of semi-implicit Euler over " + sig(duration, 4) +
         " s on '" + body + "' is " + sig(first.drift, 3) + " rad at h = " + step_text(first.h) +
         " and still " + sig(last.drift, 3) + " rad at h = " + step_text(last.h) +
         " (error predicted " + sig(first.lower, 4) + ".." + sig(first.upper, 4) + " m and " +
         sig(last.lower, 4) + ".." + sig(last.upper, 4) + " m, measured " + sig(first.error, 4) +
         " m and " + sig(last.error, 4) +
         " m): the error is that drift, second order in h, until h is well below "
         "12/(omega^2*T) = " +
         sig(edge, 3) + " s (" + sig(duration / edge, 3) + " steps)";
}

}  // namespace dropcheck
