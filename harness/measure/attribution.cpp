#include "harness/measure/attribution.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dropcheck {

double rounding_budget(Scalar scalar) { return scalar == Scalar::f32 ? 1e-4 : 1e-9; }

double rounding_budget(Scalar scalar, const Trajectory& law) {
  const double eps = scalar == Scalar::f32 ? 0x1p-23 : 0x1p-52;  // spacing of numbers in [1, 2)
  double scale = 0.0;
  for (const BodyState& s : law.states) scale = std::max(scale, s.position.cwiseAbs().maxCoeff());
  return std::max(rounding_budget(scalar), 0.5 * eps * scale * static_cast<double>(law.steps));
}

Attribution attribute(const Trajectory& e, const Trajectory& le, Scalar se, const Trajectory& r,
                      const Trajectory& lr, Scalar sr) {
  Attribution a;
  a.engine = e.engine;
  a.reference = r.engine;
  a.budget = rounding_budget(se, le) + rounding_budget(sr, lr);
  const std::size_t samples = std::min({e.samples(), r.samples(), le.samples(), lr.samples()});
  for (std::size_t s = 0; s < samples; ++s) {
    double final_dx = 0.0;
    for (std::size_t b = 0; b < e.bodies(); ++b) {
      const Vec3 diff = e.at(s, b).position - r.at(s, b).position;
      const Vec3 law = le.at(s, b).position - lr.at(s, b).position;
      a.total = std::max(a.total, diff.norm());
      a.law_part = std::max(a.law_part, law.norm());
      a.residual = std::max(a.residual, (diff - law).norm());
      final_dx = std::max(final_dx, diff.norm());
    }
    a.final_total = final_dx;
    a.final_t = e.time(s);
  }
  return a;
}

std::string format_length(double m) {
  char buf[48];
  const double x = std::abs(m);
  if (x == 0.0) return "0 m";
  if (!std::isfinite(x)) return "inf";
  if (x >= 1.0) std::snprintf(buf, sizeof buf, "%.3g m", m);
  else if (x >= 1e-2) std::snprintf(buf, sizeof buf, "%.3g cm", m * 1e2);
  else if (x >= 1e-3) std::snprintf(buf, sizeof buf, "%.3g mm", m * 1e3);
  else if (x >= 1e-6) std::snprintf(buf, sizeof buf, "%.3g um", m * 1e6);
  else std::snprintf(buf, sizeof buf, "%.2g m", m);
  return buf;
}

std::string Attribution::sentence() const {
  char buf[512];
  std::string why;
  if (total == 0.0) {
    why = "identical";
  } else if (explained() && law_part <= budget) {
    // Same discrete law (or laws that differ by less than rounding): nothing for the laws to split.
    std::snprintf(buf, sizeof buf, "the two discrete laws agree, so all of it is rounding (residual %s, budget %s)",
                  format_length(residual).c_str(), format_length(budget).c_str());
    why = buf;
  } else if (explained()) {
    const double share = law_part >= total ? 100.0 : 100.0 * law_part / total;
    std::snprintf(buf, sizeof buf, "%s from the two discrete laws (damping order); residual %s, within rounding",
                  share >= 99.95 ? "all of it" : (std::to_string(static_cast<int>(share)) + "%").c_str(),
                  format_length(residual).c_str());
    why = buf;
  } else {
    std::snprintf(buf, sizeof buf, "the laws explain %s; UNEXPLAINED residual %s (rounding allows %s)",
                  format_length(law_part).c_str(), format_length(residual).c_str(),
                  format_length(budget).c_str());
    why = buf;
  }
  std::snprintf(buf, sizeof buf, "%s vs %s: %s at t = %g s (max %s), %s.", engine.c_str(),
                reference.c_str(), format_length(final_total).c_str(), final_t,
                format_length(total).c_str(), why.c_str());
  return buf;
}

}  // namespace dropcheck
