#include "harness/judge/landing_expectation.hpp"

#include <cmath>

#include "harness/core/number_format.hpp"
#include "harness/judge/tolerances.hpp"

namespace dropcheck {

LandingExpectation landing_expectation(const EngineInfo& info, const Scene& scene, double h,
                                       const LandingSetup& setup) {
  LandingExpectation e{info.rest_offset, info.rest_tolerance, climb_path(info, scene, h, setup)};
  e.one_step_fall = one_step_fall(info.law, decay_per_step(scene, h), h, -scene.world.gravity.y());
  if (!e.climb) e.climb = replayed_landing_path(info, scene, h, setup);
  if (e.climb) {
    e.rest_offset = e.climb->y.back() - setup.rest_height;
    e.tolerance = e.climb->replayed.empty() ? tolerance::kClimbPath : tolerance::kReplayedPath;
  }
  return e;
}

namespace {

// Rest and stillness, or the path, without the departure.
LandingEnd landing_end(const Trajectory& run, const LandingSetup& setup,
                       const LandingObservation& seen, const LandingExpectation& expected,
                       const EngineInfo& info, const StillCriteria& still) {
  LandingEnd end;
  end.rests = std::abs(seen.rest_offset - expected.rest_offset) <= expected.tolerance;
  if (expected.climb) {
    end.off_path = off_climb(run, setup, *expected.climb);
    end.settled = end.off_path <= expected.tolerance;
    if (!expected.climb->replayed.empty()) {
      end.text =
          printf_string("follows its %s: %.2g m off it at worst, ends at %.3g m/s",
                        expected.climb->replayed.c_str(), end.off_path, expected.climb->climb) +
          (end.settled ? "" : " DEPARTS");
      return end;
    }
    end.text = printf_string(
                   "climbs at %.3g m/s as its law (push-out capped at %g m/s), %.2g m "
                   "off it at worst",
                   expected.climb->climb, info.relative_cfm.max_push, end.off_path) +
               (end.settled ? "" : " DEPARTS");
    return end;
  }
  // A run that ends less than the window after first contact cannot show stillness: not judged.
  const bool short_run = seen.first_contact_step >= 0 && !seen.still_judged;
  end.settled = seen.still || short_run;
  end.text = short_run ? printf_string(
                             "stillness not judged: the run ends %.3g s after first "
                             "contact (window %.3g s)",
                             seen.after_contact, still.seconds)
                       : printf_string("still: max |v| %.3g m/s, range %.3g m over the last %.3g s",
                                       seen.still_speed, seen.still_range, still.seconds) +
                             (seen.still ? "" : " NOT STILL");
  return end;
}

// The first step the landing departs, from its first failing quantity.
RestingDeparture landing_departure(const Trajectory& run, const LandingSetup& setup,
                                   const LandingObservation& seen,
                                   const LandingExpectation& expected, const LandingEnd& end,
                                   const StillCriteria& still) {
  const double rest_y = setup.rest_height + expected.rest_offset;
  if (expected.climb)
    return end.settled ? RestingDeparture{}
                       : path_departure(run, setup.body, expected.climb->y, expected.tolerance);
  RestingDeparture d;
  if (end.rebounds)
    d = rebound_departure(run, setup.body, seen.first_contact_step, rest_y, tolerance::kMaxRebound);
  if (!end.rests)
    d = earlier(d, rest_departure(run, setup.body, rest_y, expected.tolerance, setup.weight,
                                  expected.one_step_fall));
  if (!end.settled && seen.still_judged)
    d = earlier(d, stillness_departure(run, setup.body,
                                       run.recorded.back() - std::llround(still.seconds / run.h),
                                       still.max_speed, still.max_range));
  return d;
}

}  // namespace

LandingEnd judge_landing_end(const Trajectory& run, const LandingSetup& setup,
                             const LandingObservation& seen, const LandingExpectation& expected,
                             const EngineInfo& info, const StillCriteria& still) {
  LandingEnd end = landing_end(run, setup, seen, expected, info, still);
  // NaN (no contact) counts as a rebound: nothing shows it came to rest.
  end.rebounds =
      !expected.climb && !(seen.rebound - expected.rest_offset <= tolerance::kMaxRebound);
  if (!end.rests || !end.settled || end.rebounds)
    end.departure = landing_departure(run, setup, seen, expected, end, still);
  return end;
}

}  // namespace dropcheck
