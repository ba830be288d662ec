#include "harness/judge/metrics.hpp"

#include <cmath>
#include <limits>

namespace dropcheck {

ErrorStats compare(const Trajectory& a, const Trajectory& b, std::size_t body, double tolerance) {
  ErrorStats s;
  const double eps = 1e-9 * std::max(a.h, b.h);
  double sum_dx2 = 0.0, sum_dv2 = 0.0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < a.samples(); ++i) {
    const double t = a.time(i);
    while (j < b.samples() && b.time(j) < t - eps) ++j;
    if (j == b.samples()) break;
    if (std::abs(b.time(j) - t) > eps) continue;
    const double dx = (a.at(i, body).position - b.at(j, body).position).norm();
    const double dv = (a.at(i, body).velocity - b.at(j, body).velocity).norm();
    s.max_dx = std::max(s.max_dx, dx);
    s.max_dv = std::max(s.max_dv, dv);
    sum_dx2 += dx * dx;
    sum_dv2 += dv * dv;
    s.final_dx = dx;
    s.final_dv = dv;
    s.final_t = t;
    if (s.diverged_at < 0.0 && dx > tolerance) s.diverged_at = t;
    ++s.samples;
  }
  if (s.samples) {
    s.rms_dx = std::sqrt(sum_dx2 / static_cast<double>(s.samples));
    s.rms_dv = std::sqrt(sum_dv2 / static_cast<double>(s.samples));
  }
  return s;
}

ErrorStats compare_worst(const Trajectory& a, const Trajectory& b, double tolerance) {
  ErrorStats worst;
  bool any = false;
  for (std::size_t body = 0; body < a.bodies(); ++body) {
    ErrorStats s = compare(a, b, body, tolerance);
    if (!any || s.max_dx > worst.max_dx) worst = s;
    any = true;
  }
  return worst;
}

std::vector<double> observed_orders(std::span<const double> h, std::span<const double> error) {
  std::vector<double> p;
  for (std::size_t i = 0; i + 1 < h.size(); ++i) {
    if (error[i] <= 0.0 || error[i + 1] <= 0.0) {
      p.push_back(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    p.push_back(std::log(error[i] / error[i + 1]) / std::log(h[i] / h[i + 1]));
  }
  return p;
}

}  // namespace dropcheck
