#include "harness/study/sweep.hpp"

#include <algorithm>
#include <cmath>

#include "harness/core/number_format.hpp"
#include "harness/core/timestep.hpp"
#include "harness/judge/attribution.hpp"
#include "harness/judge/metrics.hpp"
#include "harness/judge/stability_classify.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/oracles/stability_theory.hpp"

namespace dropcheck {
namespace {

// h/n written as "1/(N*n)" when h is "1/N", else in seconds.
Timestep divided(const Timestep& h, int n) {
  return {h.seconds / n, divided_step_text(h.text, h.seconds, n)};
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
  for (std::size_t i = 0; i < h.size(); ++i) o.text += (i ? ", " : "") + sig(h[i], 4);
  o.text += "; observed orders";
  for (double p : o.orders)
    o.text += std::isfinite(p) ? " " + fixed(p, 3) : std::string(" undefined");
  return o;
}

namespace {

// One named product of a rate and the step.
struct Product {
  std::string text;
  double value = 0.0;
};

// The products of `scene`'s rates with h. A first-order law's error is C*h only once every term
// of its expansion beyond the first is small against it: the world damping's exp(-k*h) = 1 - k*h +
// (k*h)^2/2 - ..., a spring's (omega*h)^2 and gamma*h in its per-step map, and, over a long run,
// the phase: semi-implicit Euler turns an undamped spring by theta = 2*asin(omega*h/2) per step
// instead of omega*h (eigenvalues of [[1 - (w*h)^2, h], [-w^2*h, 1]] are exp(+-i*theta)), a
// relative frequency error r = theta/(omega*h) - 1 = (omega*h)^2/24 + ..., so after T seconds the
// phase is off by omega*T*r: second order in h, but multiplied by T (or by the 2/(gamma + k)
// seconds a damped oscillation lasts). While omega*T*r is not small the error is that drift (or
// saturates at twice the amplitude), not the first-order term.
std::vector<Product> products(const Scene& scene, double h) {
  std::vector<Product> out;
  if (scene.world.damping_rate > 0.0)
    out.push_back(
        {printf_string("k*h = %.3g", scene.world.damping_rate * h), scene.world.damping_rate * h});
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].is_static) continue;
    const std::optional<SpringModel> s = body_spring(scene, i);
    if (!s) continue;
    const std::string on = " on '" + scene.bodies[i].name + "'";
    const double wh = s->omega * h;
    out.push_back({printf_string("omega*h = %.3g", wh) + on, wh});
    if (s->gamma > 0.0)
      out.push_back({printf_string("gamma*h = %.3g", s->gamma * h) + on, s->gamma * h});
    if (wh < 2.0) {
      // The drift matters while the oscillation lasts: its amplitude decays as exp(-(gamma +
      // k)*t/2).
      const double damping = s->gamma + s->k;
      const double lasts = damping > 0.0 ? std::min(scene.duration, 2.0 / damping) : scene.duration;
      const double drift = s->omega * lasts * (2.0 * std::asin(0.5 * wh) / wh - 1.0);
      out.push_back(
          {printf_string("phase drift omega*T*(relative frequency error) = %.3g rad", drift) + on,
           drift});
    }
  }
  return out;
}

}  // namespace

std::string step_text(double h) {
  const double n = std::round(1.0 / h);
  if (n >= 1.0 && same_step(1.0 / n, h)) return "1/" + std::to_string(static_cast<long long>(n));
  return printf_string("%.4g", h);
}

std::string pre_asymptotic_cause(const Scene& scene, double h) {
  const std::vector<Product> all = products(scene, h);
  if (all.empty()) return "no rate in the scene (cause not named)";
  std::string out;
  const Product* largest = &all.front();
  for (const Product& p : all) {
    if (p.value > largest->value) largest = &p;
    if (p.value > tolerance::kPreAsymptoticProduct) out += (out.empty() ? "" : ", ") + p.text;
  }
  if (out.empty()) out = largest->text;
  return out + " at the sweep's finest step h = " + step_text(h) + " s";
}

ExtendedSweep extend_sweep(const Scene& scene, std::vector<double> h, std::vector<double> e,
                           double noise, const ErrorAt& error_at, std::int64_t max_added) {
  ExtendedSweep x{std::move(h), std::move(e), 0, {}, false, {}};
  std::int64_t spent = 0;
  auto judge = [&] {
    x.estimate = estimate_order(x.h, x.e, noise);
    const double last = x.estimate.orders.empty() ? NAN : x.estimate.orders.back();
    x.reached = x.estimate.measurable && last >= tolerance::kFirstOrderLow &&
                last <= tolerance::kFirstOrderHigh;
  };
  judge();
  while (!x.reached) {
    // An error that is not finite (the closed form or the run overflowed) stays so at any step.
    if (!x.e.empty() && !std::isfinite(x.e.back())) {
      x.stopped = "the error at h = " + step_text(x.h.back()) + " is " + g3(x.e.back()) +
                  ", which no finer step makes finite";
      return x;
    }
    const double next = 0.5 * x.h.back();
    const std::int64_t steps = step_count(scene, next);
    if (steps > kMaxSteps) {
      x.stopped = "h = " + step_text(next) + " would take more than the step limit";
      return x;
    }
    if (spent + steps > max_added) {
      x.stopped = "h = " + step_text(next) + " would exceed the extension's cost cap of " +
                  std::to_string(max_added) + " added steps";
      return x;
    }
    spent += steps;
    std::string why;
    const std::optional<double> err = error_at(next, why);
    if (!err) {
      x.stopped = "at h = " + step_text(next) + ": " + why;
      return x;
    }
    x.h.push_back(next);
    x.e.push_back(*err);
    ++x.added;
    judge();
  }
  return x;
}

}  // namespace dropcheck
