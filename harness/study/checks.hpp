// The checks behind `dropcheck check` and `ctest -L cross`: each one passes or fails with a message
// a person can act on (scene, engine, body, step, both values).
#pragma once

#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/judge/tolerances.hpp"

namespace dropcheck {

struct CheckResult {
  std::string scene, engine;
  std::string check;  // "own law at h = 1/60", "divergence from ours-f64", "landing", ...
  bool passed = false;
  // Set on a passed check whose engine met a limit of its own law or design rather than a fault
  // (its law is unstable at h, it has no continuous collision, ...): the cause, one sentence.
  // Printed as LIMIT; never counted as a failure.
  std::string limit;
  std::string message;  // the measured figures; on failure, what differs and where
};

// The steps the own-law check runs at: own_law_steps (harness/study/sweep.hpp).
std::vector<Timestep> conformance_steps(const Scene& scene);

// Oracle 2: on a free-flight scene, the engine follows its own declared discrete law at step h to
// within its own-law tolerance (harness/judge/own_law.hpp); a reported clamp ends the comparison.
CheckResult check_own_law(const Scene& scene, const EngineFactory& make, const Timestep& h);

// Cross-engine: over the scene's sweep, the engine's divergence from `reference` is explained by
// the two laws (residual within rounding) and, where the laws differ, shrinks at first order
// (observed order 0.9-1.1: the signature of a damping-order difference and nothing else). For the
// reference itself: its error against the analytic solution shrinks at first order. A sweep out of
// band while the engines follow their laws is extended (extend_sweep, at most `extension_steps`
// added steps); a reference whose extension stops short passes as a LIMIT when the phase drift of
// its law explains every error (harness/study/phase_drift.hpp), and fails otherwise.
CheckResult check_divergence(const Scene& scene, const EngineFactory& make,
                             const EngineFactory& reference,
                             std::int64_t extension_steps = tolerance::kExtensionSteps);

// Oracle 1 for contacts: each dynamic body over a static floor makes first contact within one step
// of its own discrete law's contact step, rebounds no higher than rest + tolerance::kMaxRebound,
// rests within the engine's declared rest_offset +- rest_tolerance, and is still over the last 2 s.
CheckResult check_landing(const Scene& scene, const EngineFactory& make, const Timestep& h);

// A slide to a stop (harness/oracles/contact_laws.hpp): each sliding body stops at the step the
// ideal clamp law predicts for the engine's declared friction model, after its distance (within
// tolerance::kSlideDistance). A body that stops as another model predicts is named with that model.
CheckResult check_slide(const Scene& scene, const EngineFactory& make, const Timestep& h);

// A dropped sphere's bounces (harness/oracles/contact_laws.hpp): each bouncing body's path, every
// step, within tolerance::kBouncePath of the engine's declared bounce law (EngineInfo::bounce_law);
// where that law departs from the ideal one, the members that move it are named with its figures.
CheckResult check_bounce(const Scene& scene, const EngineFactory& make, const Timestep& h);

// The resting stacks of the scene (harness/oracles/stack.hpp) at step h: every body's sink within
// its engine's stack law, its drift and its stillness within the engine's stated bounds
// (harness/core/stack_law.hpp); a stack its solver's sweeps cannot hold is a named limit.
CheckResult check_stack(const Scene& scene, const EngineFactory& make, const Timestep& h);

// Every check that applies to `scene` on one engine (free flight: own law at three steps and
// divergence; contacts: a slide, else landing). An engine that cannot run the scene gives no
// results.
std::vector<CheckResult> check_scene(const Scene& scene, const EngineFactory& make,
                                     const EngineFactory& reference);

}  // namespace dropcheck
