#include "harness/study/accuracy_response.hpp"

#include "harness/core/number_format.hpp"
#include "harness/judge/metrics.hpp"
#include "harness/judge/own_law.hpp"
#include "harness/oracles/analytic.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {

bool AccuracyResponse::within() const {
  if (!unavailable.empty()) return false;
  for (const AccuracyPoint& p : points)
    if (!p.within()) return false;
  return true;
}

AccuracyResponse error_per_accuracy(Engine& engine, const Scene& scene, double h) {
  AccuracyResponse r;
  if (const std::string why = analytic_unavailable(scene); !why.empty()) {
    r.unavailable = "no closed form (" + why + ")";
    return r;
  }
  const double kept = engine.info().accuracy;
  const Trajectory exact = *analytic_trajectory(scene, h);
  for (const double a : kAccuraciesMeasured) {
    if (!engine.set_accuracy(a)) {
      r.unavailable = engine.info().name + " takes no accuracy: it is not error-controlled";
      break;
    }
    const Trajectory run = run_scene(engine, scene, h);
    if (run.status != RunStatus::ok) {
      r.unavailable = "the run at accuracy " + g3(a) + " failed: " + run.failure;
      break;
    }
    const ErrorStats d = compare_worst(run, exact, 0.0);
    const OwnLawTolerance budget = own_law_tolerance(engine.info(), exact, run.engine_steps);
    r.points.push_back({a, d.max_dx, d.max_dv, run.engine_steps, budget.x, budget.v});
  }
  if (kept > 0.0) engine.set_accuracy(kept);
  return r;
}

}  // namespace dropcheck
