// Oracle 2 in the engine's own arithmetic: its discrete law iterated in its own scalar (float or
// double) with its own operation order, as its source writes it (EngineInfo::arithmetic).
//
// A correct engine then matches the prediction to the bit (0 m), so the own-law tolerance is a few
// ulps (harness/judge/tolerances.hpp), and the cost of the scalar becomes a measured figure: this
// prediction against the long-double law (harness/oracles/discrete_law.hpp), the "precision part".
//   phi_multiply (ours, ours/physics.hpp):      v = v + g*h; v = v + (F/m)*h; v = v*phi; x = x +
//   v*h pade (Box2D 2.4.1, b2Island::Solve):        v = v + (h*(1/m))*((1*m)*g + F);
//                                               v = v*(1/(1 + h*c)); x = x + h*v
//   per_second_power (Bullet, double):         v = v*(1 - d)^h (before forces); v = v + (g + F/m)*h
// with phi = exp(-k*h), c = expm1(k*h)/h and d = 1 - exp(-k) computed in double and rounded once to
// the scalar, as the adapters do. The damping factor sits where the engine's Law puts it. Free
// flight only.
#pragma once

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {

// True when the harness predicts `info` in its own arithmetic (arithmetic != other).
bool arithmetic_copied(const EngineInfo& info);

// True when that prediction copies the engine's whole operation order, to the bit (ours, Box2D).
bool order_copied(const EngineInfo& info);

// The engine's law in its own arithmetic when copied; otherwise the long-double law
// (predict_discrete), which is then the closest prediction the harness has.
Trajectory predict_own_arithmetic(const EngineInfo& info, const Scene& scene, double h,
                                  const RunOptions& options = {});

}  // namespace dropcheck
