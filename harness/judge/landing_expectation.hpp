// What a landing is judged against, by `dropcheck check` and the report alike: the rest offset the
// adapter declares (EngineInfo::rest_offset, rest_tolerance) and stillness at the end; or, for an
// engine whose landing has a climb path (harness/oracles/landing.hpp: DART's capped push-out),
// that path within tolerance::kClimbPath at every step, its end the expected rest offset.
#pragma once

#include <optional>
#include <string>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"
#include "harness/judge/resting_departure.hpp"
#include "harness/oracles/landing.hpp"

namespace dropcheck {

struct LandingExpectation {
  double rest_offset = 0.0;        // m: the centre's expected final offset from the rest height
  double tolerance = 0.0;          // m
  std::optional<ClimbPath> climb;  // set: judged by the path, not by stillness
  // m: how far its law moves a body in one step from rest (g*h^2*phi for semi-implicit Euler):
  // what a contact resolved after the position update leaves it below its rest, the cause a rest
  // height that far low is named by.
  double one_step_fall = 0.0;
};

LandingExpectation landing_expectation(const EngineInfo& info, const Scene& scene, double h,
                                       const LandingSetup& setup);

// How a run's landing meets its expectation beyond first contact and rebound.
struct LandingEnd {
  bool rests = false;     // its final offset within tolerance of the expected
  bool settled = false;   // still at the end, or (a climb path) on the path at every step
  double off_path = 0.0;  // m: a climb path's largest |y - path|
  // "still: max |v| 1e-07 m/s, range 5e-09 m over the last 2 s" or "climbs at 0.000998 m/s as its
  // law (push-out capped at 0.001 m/s), 2e-13 m off it", with NOT STILL or DEPARTS when it fails.
  std::string text;
  // When it fails (rebound, rest height, stillness, its path): the first step it departs, and how.
  RestingDeparture departure;
  bool rebounds = false;  // above its expected rest by more than tolerance::kMaxRebound after
                          // first contact, or no contact at all (a body on a path is held to the
                          // path instead): the one rebound judgement of check and report
};
LandingEnd judge_landing_end(const Trajectory& run, const LandingSetup& setup,
                             const LandingObservation& seen, const LandingExpectation& expected,
                             const EngineInfo& info, const StillCriteria& still = {});

}  // namespace dropcheck
