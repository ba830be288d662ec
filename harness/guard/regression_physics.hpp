// Tier 3 of the regression guard (regression_physics.cpp): a fresh run against the two oracles.
#pragma once

#include <functional>
#include <vector>

#include "harness/guard/baseline.hpp"
#include "harness/guard/regression.hpp"
#include "harness/study/checks.hpp"

namespace dropcheck {

// Tier 3: `now` (a fresh make_baseline, not a parsed file) follows its own discrete law within its
// own-law tolerance at every h of the sweep, and its error against the analytic solution shrinks
// at first order as h halves (harness/judge/tolerances.hpp). A departure names what the run
// follows instead (a member of the law family: "first-order, follows explicit Euler (...);
// differs from the baseline by 3.2 cm at h = 1/60", measured against `baseline` when given) or
// "order 0.03: not consistent".
// The stored sweep cannot see the limits of a law (a step where it is unstable, a sweep kept
// pre-asymptotic by its phase drift or stiffness): when it fails and `core` is given, the tier asks
// the measurement core, the checks `dropcheck check` runs (check_scene of the engine against
// itself), and passes when every one of them passes, naming their LIMITs; when one fails, the
// tier's own message stands.
// A contact scene (`contacts`) stores no free-flight law: the tier is the core's contact checks
// (landing, slide, bounce, stack, each against the engine's declared contact law), failed with the
// first one that fails, its step and quantity named; skipped without a core.
using CoreChecks = std::function<std::vector<CheckResult>()>;
TierResult check_physics(const Baseline& now, const Baseline* baseline = nullptr,
                         const CoreChecks& core = {}, bool contacts = false);

// The checks `dropcheck check` runs on `engine` in `scene` against `reference` (check_scene), as
// check_physics asks for them; none (an empty function) without a reference.
CoreChecks core_checks(const Scene& scene, const EngineFactory& engine,
                       const EngineFactory& reference);

}  // namespace dropcheck
