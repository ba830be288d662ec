// Oracle 2: an engine's own discrete law, iterated in long double.
//
// With the per-step decay phi = exp(-k*h) and a = g + F/m (F from harness/core/forces.hpp evaluated
// on the predicted state at the start of the step), a free body follows its member of the law
// family (harness/core/law.hpp). The RK4 member instead integrates v' = g + F/m - k*v over four
// stages, each spring pulling from the stage's state (stage_force). The error-controlled member's
// law is the continuous model: its closed form (harness/oracles/analytic.hpp). An engine that
// differs from its own law by more than rounding has an adapter bug. Valid for free flight only
// (contacts are not modelled).
#pragma once

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {

Trajectory predict_discrete(Law law, const Scene& scene, double h, const RunOptions& options = {});

}  // namespace dropcheck
