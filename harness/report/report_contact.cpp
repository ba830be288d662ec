#include "harness/report/report_contact.hpp"

#include "harness/core/number_format.hpp"
#include "harness/measure/slide_verdict.hpp"
#include "harness/measure/tolerances.hpp"
#include "harness/report/report_format.hpp"

namespace dropcheck {

bool off_slide_law(const SceneEvaluation& se, const EngineEvaluation& ev) {
  if (!ev.ran() || ev.at_default().run.status != RunStatus::ok) return false;
  for (const SlideSetup& s : slide_setups(se.scene)) {
    const SlideVerdict v =
        judge_slide(ev.at_default().run, s, ev.info.friction_model, se.scene.timestep.seconds);
    if (v.exact && !v.follows) return true;
  }
  return false;
}

std::string slide_section(const SceneEvaluation& se) {
  const std::vector<SlideSetup> slides = slide_setups(se.scene);
  if (slides.empty()) return {};
  MarkdownTable t({"engine", "body", "friction model", "stop step", "distance (m)",
                   "clamp law: step", "clamp law: distance (m)", "closed form: t (s)",
                   "closed form: distance (m)", "follows its law"},
                  "lll");
  const double h = se.scene.timestep.seconds;
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran() || ev.at_default().run.status != RunStatus::ok) continue;
    for (const SlideSetup& s : slides) {
      const SlideVerdict v = judge_slide(ev.at_default().run, s, ev.info.friction_model, h);
      const bool stopped = v.seen.stop_step >= 0;
      t.add({ev.name, se.scene.bodies[s.body].name, to_string(v.model),
             stopped ? std::to_string(v.seen.stop_step) : "never",
             printf_string("%.7g", v.seen.distance),
             v.exact ? std::to_string(v.law.stop_step) : kNone,
             v.exact ? printf_string("%.7g", v.law.step_distance) : kNone,
             v.exact ? printf_string("%.5g", v.law.stop_time) : kNone,
             v.exact ? printf_string("%.5g", v.law.distance) : kNone,
             !v.exact    ? "not judged (angle)"
             : v.follows ? "yes"
             : v.instead ? std::string("**NO**: the ") + to_string(*v.instead) + "'s law"
                         : std::string("**NO**")});
    }
  }
  return "#### Slide to a stop at h = " + se.scene.timestep.text +
         "\n\nThe stop step is the first step whose horizontal speed is at most " +
         printf_string("%.0e", tolerance::kStoppedSpeed) +
         " m/s; the clamp law v <- max(v - a*h, 0), x += h*v is the ideal discrete slide of the "
         "engine's friction model (a cone decelerates the slip by mu*g, a box pyramid each tangent "
         "axis by mu*g, a sum pyramid shares mu*g between them: docs/contact.md).\n\n" +
         t.str() + "\n";
}

}  // namespace dropcheck
