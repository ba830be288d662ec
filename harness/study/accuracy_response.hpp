// How an error-controlled engine's error answers the accuracy it is asked for: the variable-step
// member's counterpart of the order of convergence (closed_form_order.hpp), measured where a user
// asks `dropcheck identify --engine` of such an engine. Its law is the continuous model, so it is
// judged against the scene's closed form at each accuracy, within that accuracy's budget
// (own_law_tolerance, harness/judge/own_law.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"

namespace dropcheck {

// The accuracies asked for, loosest first: Simbody's default and three tighter by 1000 each.
inline constexpr double kAccuraciesMeasured[] = {1e-3, 1e-6, 1e-9, 1e-12};

struct AccuracyPoint {
  double accuracy = 0.0;
  double error_x = 0.0;  // max |x - closed form| over the run (m)
  double error_v = 0.0;  // max |v - closed form| (m/s)
  std::int64_t engine_steps = 0;
  double budget_x = 0.0, budget_v = 0.0;  // the accuracy's budget (m, m/s)

  bool within() const { return error_x <= budget_x && error_v <= budget_v; }
};

struct AccuracyResponse {
  std::vector<AccuracyPoint> points;  // one per kAccuraciesMeasured
  std::string unavailable;            // why nothing was measured; "" when it was

  bool within() const;  // every point within its budget
};

// Runs `engine` (error-controlled: it accepts set_accuracy) on `scene` at step h once per accuracy
// of kAccuraciesMeasured, and leaves it at the accuracy it had.
AccuracyResponse error_per_accuracy(Engine& engine, const Scene& scene, double h);

}  // namespace dropcheck
