#include "harness/judge/stability_contact.hpp"

#include <algorithm>

#include "harness/judge/contact_departures.hpp"

namespace dropcheck {

Verdict classify_engine_run(const Scene& scene, const Trajectory& run, const EngineInfo& info,
                            const ClassifyOptions& options) {
  ClassifyOptions o = options;
  o.resting_lift = std::max(info.rest_offset, 0.0) + info.stack_law.still_bound;
  Verdict v = classify_run(scene, run, info.scalar, o);
  const bool every_step = !run.recorded.empty() &&
                          run.recorded.size() == static_cast<std::size_t>(run.recorded.back()) + 1;
  if (run.status != RunStatus::ok || !every_step || !scene.world.contacts) return v;
  for (const ContactDeparture& d : contact_departures(scene, run, info, run.h))
    v.failures.push_back({FailureMode::off_contact_law, run.body_names[d.body], d.step,
                          "body '" + run.body_names[d.body] + "': " + d.what});
  std::stable_sort(v.failures.begin(), v.failures.end(), [](const Failure& a, const Failure& b) {
    return a.mode != b.mode ? a.mode < b.mode : a.step < b.step;
  });
  return v;
}

}  // namespace dropcheck
