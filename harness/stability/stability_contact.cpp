#include "harness/stability/stability_contact.hpp"

#include <algorithm>

#include "harness/measure/bounce_verdict.hpp"
#include "harness/measure/slide_verdict.hpp"
#include "harness/measure/stack_verdict.hpp"

namespace dropcheck {
namespace {

// The first departure of each contact law of the scene in `run`, appended to `out`.
void contact_law_failures(const Scene& scene, const Trajectory& run, const EngineInfo& info,
                          std::vector<Failure>& out) {
  const double h = run.h;
  auto add = [&](std::size_t body, std::int64_t step, const std::string& what) {
    out.push_back({FailureMode::off_contact_law, run.body_names[body], step,
                   "body '" + run.body_names[body] + "': " + what});
  };
  for (const SlideSetup& s : slide_setups(scene)) {
    const SlideVerdict v = judge_slide(run, s, info.friction_model, h);
    if (v.exact && !v.follows)
      add(s.body, v.seen.stop_step >= 0 ? v.seen.stop_step : run.recorded.back(),
          "slide " + v.sentence());
  }
  for (const BounceSetup& s : bounce_setups(scene)) {
    const BounceVerdict v = judge_bounce(run, s, info.bounce_law, h);
    if (!v.follows) add(s.body, v.worst_step, "bounce " + v.sentence());
  }
  for (const StackSetup& s : stack_setups(scene))
    for (const StackBodyVerdict& v : judge_stack(run, s, info, h))
      if (!v.passes()) add(v.body, run.recorded.back(), "in a stack " + v.sentence());
}

}  // namespace

Verdict classify_engine_run(const Scene& scene, const Trajectory& run, const EngineInfo& info,
                            const ClassifyOptions& options) {
  ClassifyOptions o = options;
  o.resting_lift = std::max(info.rest_offset, 0.0) + info.stack_law.still_bound;
  Verdict v = classify_run(scene, run, info.scalar, o);
  const bool every_step = !run.recorded.empty() &&
                          run.recorded.size() == static_cast<std::size_t>(run.recorded.back()) + 1;
  if (run.status != RunStatus::ok || !every_step || !scene.world.contacts) return v;
  contact_law_failures(scene, run, info, v.failures);
  std::stable_sort(v.failures.begin(), v.failures.end(), [](const Failure& a, const Failure& b) {
    return a.mode != b.mode ? a.mode < b.mode : a.step < b.step;
  });
  return v;
}

}  // namespace dropcheck
