#include "harness/judge/contact_departures.hpp"

#include "harness/judge/bounce_verdict.hpp"
#include "harness/judge/slide_verdict.hpp"
#include "harness/judge/stack_verdict.hpp"
#include "harness/judge/turned_verdict.hpp"

namespace dropcheck {

std::vector<ContactDeparture> contact_departures(const Scene& scene, const Trajectory& run,
                                                 const EngineInfo& info, double h) {
  std::vector<ContactDeparture> out;
  if (run.samples() == 0) return out;
  for (const SlideSetup& s : slide_setups(scene)) {
    const SlideVerdict v = judge_slide(run, scene, s, info, h);
    if (!v.passes())
      out.push_back({ContactLaw::slide, s.body,
                     v.first_off >= 0        ? v.first_off
                     : v.seen.stop_step >= 0 ? v.seen.stop_step
                                             : run.recorded.back(),
                     "slide " + v.sentence()});
  }
  for (const BounceSetup& s : bounce_setups(scene)) {
    const BounceVerdict v = judge_bounce(run, scene, s, info, h);
    if (!v.follows)
      out.push_back({ContactLaw::bounce, s.body, v.first_step, "bounce " + v.sentence()});
  }
  for (const StackSetup& s : stack_setups(scene))
    for (const StackBodyVerdict& v : judge_stack(run, s, info, h))
      if (!v.passes())
        out.push_back(
            {ContactLaw::stack, v.body, run.recorded.back(), "in a stack " + v.sentence()});
  if (needs_rotation(scene) && info.turned_contact != TurnedContact::not_declared) {
    const TurnedVerdict v = judge_turned_contact(scene, info, run);
    if (v.not_judged.empty() && !v.follows())
      for (std::size_t b = 0; b < scene.bodies.size(); ++b)
        if (!scene.bodies[b].is_static)
          out.push_back({ContactLaw::turned, b, v.first_departure, "landing " + v.sentence()});
  }
  return out;
}

}  // namespace dropcheck
