#include "harness/study/closed_form_order.hpp"

#include <cmath>

#include "harness/core/number_format.hpp"
#include "harness/judge/metrics.hpp"
#include "harness/judge/own_law.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/oracles/analytic.hpp"
#include "harness/oracles/own_arithmetic.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {

ClosedFormOrder order_against_closed_form(Engine& engine, const Scene& scene, double h) {
  ClosedFormOrder o;
  if (const std::string why = analytic_unavailable(scene); !why.empty()) {
    o.unavailable = "no closed form (" + why + ")";
    return o;
  }
  const EngineInfo info = engine.info();
  for (const double step : {2.0 * h, h, 0.5 * h}) {
    const Trajectory run = run_scene(engine, scene, step);
    if (run.status != RunStatus::ok) {
      o.unavailable = "the run at h = " + step_text(step) + " failed: " + run.failure;
      return o;
    }
    const double error = compare_worst(run, *analytic_trajectory(scene, step), 0.0).max_dx;
    const double noise = tolerance::kOrderMeasurableFactor *
                         own_law_tolerance(info, predict_own_arithmetic(info, scene, step)).x;
    if (error <= noise) {
      o.dropped += (o.dropped.empty() ? "" : ", ") + ("h = " + step_text(step) + ": ") +
                   format_length(error) + ", at rounding";
      continue;
    }
    o.h.push_back(step);
    o.errors.push_back(error);
  }
  if (o.h.size() < 2) {
    o.unavailable = "its error is at rounding level (" + o.dropped + ")";
    return o;
  }
  o.estimate = estimate_order(o.h, o.errors, 0.0);
  return o;
}

bool order_matches(double p, int order) {
  if (order == 1) return p >= tolerance::kFirstOrderLow && p <= tolerance::kFirstOrderHigh;
  return std::abs(p - order) <= tolerance::kFourthOrderSlack;
}

}  // namespace dropcheck
