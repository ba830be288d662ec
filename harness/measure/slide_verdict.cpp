#include "harness/measure/slide_verdict.hpp"

#include <cmath>
#include <numbers>

#include "harness/core/number_format.hpp"
#include "harness/measure/tolerances.hpp"

namespace dropcheck {
namespace {

// "step 62, 2.509472 m": a stop and the distance by then.
std::string stop_text(std::int64_t step, double distance) {
  return printf_string("step %lld, %.7g m", static_cast<long long>(step), distance);
}

bool follows_law(const SlideObservation& o, const SlideStop& law) {
  return o.stop_step == law.stop_step &&
         std::abs(o.distance - law.step_distance) <= tolerance::kSlideDistance;
}

}  // namespace

SlideVerdict judge_slide(const Trajectory& run, const SlideSetup& s, FrictionModel model,
                         double h) {
  SlideVerdict v;
  v.model = model;
  v.seen = observe_slide(run, s, tolerance::kStoppedSpeed);
  v.exact = model == FrictionModel::cone || s.angle == 0.0 ||
            std::abs(s.angle - std::numbers::pi / 4.0) < 1e-12;
  if (!v.exact) return v;
  v.law = slide_to_stop(s.v0, s.mu, s.g, h, model, s.angle);
  v.follows = follows_law(v.seen, v.law);
  if (v.follows) return v;
  for (FrictionModel other : kFrictionModels)
    if (other != model && follows_law(v.seen, slide_to_stop(s.v0, s.mu, s.g, h, other, s.angle)))
      v.instead = other;
  return v;
}

std::string SlideVerdict::sentence() const {
  std::string text = seen.stop_step < 0
                         ? printf_string("does not stop (%.7g m by the end)", seen.distance)
                         : "stops at " + stop_text(seen.stop_step, seen.distance);
  if (!exact)
    return text + "; not judged: the " + to_string(model) +
           "'s slide is exact at 0 and 45 degrees only";
  text += std::string("; its ") + to_string(model) +
          "'s clamp law: " + stop_text(law.stop_step, law.step_distance) +
          printf_string(" (continuous: %.5g s, %.5g m)", law.stop_time, law.distance);
  if (follows) return text;
  text += " DEPARTS";
  if (instead) text += std::string(": it follows the ") + to_string(*instead) + "'s law instead";
  return text;
}

}  // namespace dropcheck
