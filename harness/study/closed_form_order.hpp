// The order of convergence of one engine against a scene's closed form, measured where a user asks
// "which order is this engine?" (`dropcheck identify --engine`): 1 for every Euler member of the
// law family, 4 for RK4 (harness/core/law.hpp, order_of).
#pragma once

#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/study/sweep.hpp"

namespace dropcheck {

struct ClosedFormOrder {
  std::vector<double> h;       // the steps whose errors count, coarsest first
  std::vector<double> errors;  // max |x - closed form| at each (m)
  std::string dropped;         // steps left out, with why ("h = 1/240: 1.3e-11 m, at rounding")
  std::string unavailable;     // why there is no order at all; "" when there is one
  OrderEstimate estimate;      // over h and errors (measurable once two steps count)
};

// Runs `engine` on `scene` at 2h, h and h/2 and measures its error against the closed form. A step
// whose error is within tolerance::kOrderMeasurableFactor own-law tolerances of zero is rounding,
// not truncation, and is dropped (RK4 is exact for free fall without drag: every step dropped).
ClosedFormOrder order_against_closed_form(Engine& engine, const Scene& scene, double h);

// True when an observed order p is the declared order's: within tolerance::kFirstOrderLow..High
// of 1, within tolerance::kFourthOrderSlack of 4.
bool order_matches(double p, int order);

}  // namespace dropcheck
