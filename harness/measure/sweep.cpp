#include "harness/measure/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "harness/measure/attribution.hpp"
#include "harness/measure/metrics.hpp"
#include "harness/measure/tolerances.hpp"

namespace dropcheck {
namespace {

std::string g(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// h/n written as "1/(N*n)" when h is "1/N" and N*n fits a long long (N = 2^62 once printed
// "1/-9223372036854775808"), else in seconds.
Timestep divided(const Timestep& h, int n) {
  const long long rate = h.text.rfind("1/", 0) == 0 ? std::atoll(h.text.c_str() + 2) : 0;
  if (rate > 0 && rate <= std::numeric_limits<long long>::max() / n)
    return {h.seconds / n, "1/" + std::to_string(rate * n)};
  return {h.seconds / n, g("%.6g", h.seconds / n)};
}

}  // namespace

bool same_step(double a, double b) {
  return std::abs(a - b) <= 1e-12 * std::max(a, b);
}

std::vector<Timestep> scene_sweep(const Scene& scene) {
  std::vector<Timestep> out = scene.timesteps;
  out.push_back(scene.timestep);
  std::stable_sort(out.begin(), out.end(),
                   [](const Timestep& a, const Timestep& b) { return a.seconds > b.seconds; });
  auto same = [](const Timestep& a, const Timestep& b) { return same_step(a.seconds, b.seconds); };
  out.erase(std::unique(out.begin(), out.end(), same), out.end());
  if (out.size() < 2)
    out = {scene.timestep, divided(scene.timestep, 2), divided(scene.timestep, 4)};
  return out;
}

std::size_t default_index(const std::vector<Timestep>& sweep, const Scene& scene) {
  for (std::size_t i = 0; i < sweep.size(); ++i)
    if (same_step(sweep[i].seconds, scene.timestep.seconds)) return i;
  return 0;
}

std::vector<Timestep> own_law_steps(const Scene& scene) {
  std::vector<Timestep> out{scene.timestep};
  for (const Timestep& t : scene_sweep(scene))
    if (out.size() < 3 && !same_step(t.seconds, scene.timestep.seconds)) out.push_back(t);
  return out;
}

OrderEstimate estimate_order(std::span<const double> h, std::span<const double> e, double noise) {
  OrderEstimate o;
  o.orders = observed_orders(h, e);
  o.measurable =
      !o.orders.empty() && std::all_of(e.begin(), e.end(), [&](double x) { return x > noise; });
  o.first_order = o.measurable;
  o.consistent = o.measurable;
  for (double p : o.orders) {
    o.first_order =
        o.first_order && p >= tolerance::kFirstOrderLow && p <= tolerance::kFirstOrderHigh;
    o.consistent = o.consistent && p >= tolerance::kConsistentOrder;
  }
  o.text = "max |dx| ";
  for (std::size_t i = 0; i < e.size(); ++i) o.text += (i ? ", " : "") + format_length(e[i]);
  o.text += " at h = ";
  for (std::size_t i = 0; i < h.size(); ++i) o.text += (i ? ", " : "") + g("%.4g", h[i]);
  o.text += "; observed orders";
  for (double p : o.orders) o.text += std::isfinite(p) ? g(" %.3f", p) : std::string(" undefined");
  return o;
}

}  // namespace dropcheck
