#include "harness/judge/slide_verdict.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "harness/core/number_format.hpp"
#include "harness/judge/tolerances.hpp"

namespace dropcheck {
namespace {

// "stops at step 62, 2.509472 m", "never moves" or "slides on (2.970552 m by the end)".
std::string stop_text(const SlideObservation& o) {
  if (o.stop_step < 0) return printf_string("slides on (%.7g m by the end)", o.distance);
  if (o.stop_step == 0) return "never moves";
  return printf_string("stops at step %lld, %.7g m", static_cast<long long>(o.stop_step),
                       o.distance);
}

// The largest distance between the run's path and the law's over the steps both have (a
// non-finite run is infinitely far). The law's path is as long as the run's.
double path_distance(const SlidePath& run, const SlidePath& law) {
  double worst = 0.0;
  for (std::size_t n = 0; n < std::min(run.s.size(), law.s.size()); ++n) {
    const double d = std::hypot(run.s[n] - law.s[n], run.off[n]);
    worst = std::isfinite(d) ? std::max(worst, d) : INFINITY;
  }
  return worst;
}

struct LawFit {
  SlideObservation seen;
  double off = 0.0;
  bool follows = false;
};

LawFit fit(const SlidePath& run, const SlideObservation& seen, const SlideSetup& s,
           FrictionModel model, double h) {
  const SlidePath law = slide_path(s, model, h, static_cast<std::int64_t>(run.s.size()) - 1);
  LawFit f{observe_slide(law, tolerance::kStoppedSpeed, tolerance::kSlideDistance),
           path_distance(run, law), false};
  f.follows = f.seen.stop_step == seen.stop_step && f.off <= tolerance::kSlideDistance;
  return f;
}

}  // namespace

SlideVerdict judge_slide(const Trajectory& run, const SlideSetup& s, FrictionModel model,
                         double h) {
  SlideVerdict v;
  v.model = model;
  const SlidePath path = observed_slide_path(run, s);
  v.seen = observe_slide(path, tolerance::kStoppedSpeed, tolerance::kSlideDistance);
  v.exact = exact_slide_angle(model, s.angle);
  if (!v.exact) {
    v.not_judged =
        "the " + std::string(to_string(model)) + "'s slide is exact at 0 and 45 degrees only";
    return v;
  }
  if (!run.keeps_every_step()) {
    v.exact = false;
    v.not_judged = "the run did not keep every step";
    return v;
  }
  v.law = slide_to_stop(s.v0, s.mu, s.g, h, model, s.angle, s.pull);
  v.end_continuous = slide_distance_continuous(s.v0, s.pull, slide_grip(s.mu, s.g, model, s.angle),
                                               h * static_cast<double>(path.s.size() - 1));
  const LawFit own = fit(path, v.seen, s, model, h);
  v.law_seen = own.seen;
  v.off_law = own.off;
  v.follows = own.follows;
  if (v.follows) return v;
  const SlidePath ahead = slide_steps(s, model, h, path);
  v.off_steps = path_distance(path, ahead);
  for (std::size_t n = 0; n < path.v.size(); ++n)
    v.off_steps_speed = std::max(v.off_steps_speed, std::abs(path.v[n] - ahead.v[n]));
  v.follows =
      v.off_steps <= tolerance::kSlideDistance && v.off_steps_speed <= tolerance::kStepSpeed;
  if (v.follows) return v;
  for (FrictionModel other : kFrictionModels)
    if (other != model && exact_slide_angle(other, s.angle) &&
        fit(path, v.seen, s, other, h).follows)
      v.instead = other;
  return v;
}

std::string SlideVerdict::sentence() const {
  std::string text = stop_text(seen);
  if (!exact) return text + "; not judged: " + not_judged;
  text += std::string("; its ") + to_string(model) + "'s clamp law: " + stop_text(law_seen);
  text += law.stops && law.stop_step > 0
              ? printf_string(" (continuous: %.5g s, %.5g m)", law.stop_time, law.distance)
              : printf_string(" (continuous: %.7g m by the end)", end_continuous);
  text += printf_string(", %.2g m off it", off_law);
  if (off_steps >= 0.0)
    text += printf_string(
        follows ? ", every step as its law to %.2g m and %.2g m/s (the drift is the run's "
                  "rounding)"
                : " (one step from its own state: %.2g m, %.2g m/s)",
        off_steps, off_steps_speed);
  if (follows) return text;
  text += " DEPARTS";
  if (instead) text += std::string(": it follows the ") + to_string(*instead) + "'s law instead";
  return text;
}

}  // namespace dropcheck
