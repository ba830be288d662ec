// Tier 3 of the regression guard (regression_physics.cpp): a fresh run against the two oracles.
#pragma once

#include "harness/guard/baseline.hpp"
#include "harness/guard/regression.hpp"

namespace dropcheck {

// Tier 3: `now` (a fresh make_baseline, not a parsed file) follows its own discrete law within its
// own-law tolerance at every h of the sweep, and its error against the analytic solution shrinks
// at first order as h halves (harness/measure/tolerances.hpp). A departure names what the run
// follows instead (a member of the law family: "first-order, follows explicit Euler (...);
// differs from the baseline by 3.2 cm at h = 1/60", measured against `baseline` when given) or
// "order 0.03: not consistent".
TierResult check_physics(const Baseline& now, const Baseline* baseline = nullptr);

}  // namespace dropcheck
