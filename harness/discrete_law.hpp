// Oracle 2: an engine's own discrete law, iterated in long double.
//
// With the per-step decay phi = exp(-k*h) and a = g + F/m (F from harness/forces.hpp evaluated on
// the predicted state at the start of the step), a free body follows one of (engine.hpp):
//   AfterForces:   v = phi*(v + a*h);  x += h*v
//   BeforeForces:  v = phi*v + a*h;    x += h*v
//   AfterPosition: v' = v + a*h; x += h*v'; v = phi*v'
// An engine that differs from its own law by more than rounding has an adapter bug.
// Valid for free flight only (contacts are not modelled).
#pragma once

#include "engine.hpp"
#include "runner.hpp"
#include "trajectory.hpp"

namespace dropcheck {

Trajectory predict_discrete(DampingOrder law, const Scene& scene, double h,
                            const RunOptions& options = {});

}  // namespace dropcheck
