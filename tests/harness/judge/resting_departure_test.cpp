// Tests harness/judge/resting_departure.cpp: where a body that should rest first departs, and the
// figure that names the cause, on hand-written runs of one body whose answers are known; and a
// failing landing's departure (harness/judge/landing_expectation.cpp).
#include "harness/judge/resting_departure.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <numbers>

#include "harness/judge/landing_expectation.hpp"

using namespace dropcheck;
using Catch::Contains;

namespace {

// One body, every step of h = 0.01 recorded, at height y(n) with vertical speed v(n) and x(n).
Trajectory resting_run(
    std::int64_t steps, const std::function<double(std::int64_t)>& y,
    const std::function<double(std::int64_t)>& v,
    const std::function<double(std::int64_t)>& x = [](std::int64_t) { return 0.0; }) {
  Trajectory t;
  t.h = 0.01;
  t.steps = steps;
  t.body_names = {"cube"};
  for (std::int64_t n = 0; n <= steps; ++n) {
    t.recorded.push_back(n);
    t.states.push_back({Vec3(x(n), y(n), 0.0), Vec3(0.0, v(n), 0.0)});
  }
  return t;
}

}  // namespace

TEST_CASE("A rebound departs where it rises past the limit, with its restitution",
          "[contact][landing]") {
  // Falls at 5 m/s onto the rest height 0.5 at step 10, leaves at 2.5 m/s: 0.025 m up a step.
  const Trajectory run = resting_run(
      40, [](std::int64_t n) { return n <= 10 ? 0.5 + 0.05 * (10 - n) : 0.5 + 0.025 * (n - 10); },
      [](std::int64_t n) { return n <= 10 ? -5.0 : 2.5; });
  const RestingDeparture d = rebound_departure(run, 0, 10, 0.5, 1e-3);
  CHECK(d.step == 11);
  CHECK(d.quantity == "rebound");
  CHECK_THAT(d.sentence(), Contains("first departs at step 11 (rebound)") &&
                               Contains("left the floor at 2.5 m/s after meeting it at 5 m/s") &&
                               Contains("a restitution of 0.5"));
  CHECK(rebound_departure(run, 0, 10, 0.5, 1.0).step == -1);  // never 1 m up
}

TEST_CASE("A body resting low departs where it last sank past its tolerance, a soft sag",
          "[contact][landing]") {
  // Settles to 0.01 m below 0.5 from step 20 (and passes through it once at step 5): a spring of
  // 9.8 N / 0.01 m holds a 1 kg weight there.
  const Trajectory run = resting_run(
      60, [](std::int64_t n) { return n == 5   ? 0.49
                                      : n < 20 ? 0.5
                                               : 0.49; },
      [](std::int64_t) { return 0.0; });
  const RestingDeparture d = rest_departure(run, 0, 0.5, 1e-3, 9.8);
  CHECK(d.step == 20);
  CHECK_THAT(d.cause, Contains("rests 0.01 m below") && Contains("a spring of 980 N/m"));
  CHECK(rest_departure(run, 0, 0.49, 1e-3, 9.8).step == -1);
  const Trajectory high = resting_run(
      10, [](std::int64_t) { return 0.52; }, [](std::int64_t) { return 0.0; });
  CHECK_THAT(rest_departure(high, 0, 0.5, 1e-3, 9.8).cause, Contains("rests 0.02 m above"));
}

TEST_CASE("A body that never stills departs at its first fast step: an oscillation's period",
          "[contact][landing]") {
  // v = 0.01*sin(2*pi*n/20): 20 steps per period, reversing every 10.
  const Trajectory run = resting_run(
      200, [](std::int64_t) { return 0.5; },
      [](std::int64_t n) { return 0.01 * std::sin(2 * std::numbers::pi * (n + 0.5) / 20.0); });
  const RestingDeparture d = stillness_departure(run, 0, 100, 1e-3, 1e-3);
  CHECK(d.step == 100);
  CHECK_THAT(d.cause, Contains("oscillating about its rest") && Contains("a period of about 20"));
  const Trajectory creep = resting_run(
      200, [](std::int64_t) { return 0.5; }, [](std::int64_t n) { return n < 150 ? 0.0 : -2e-3; });
  CHECK(stillness_departure(creep, 0, 100, 1e-3, 1.0).step == 150);
  CHECK_THAT(stillness_departure(creep, 0, 100, 1e-3, 1.0).cause, Contains("a creep"));
}

TEST_CASE("A height gone NaN and a slow creep past the range each name a departure",
          "[contact][landing]") {
  const Trajectory lost = resting_run(
      20, [](std::int64_t n) { return n < 12 ? 0.5 : std::nan(""); },
      [](std::int64_t) { return 0.0; });
  CHECK(rest_departure(lost, 0, 0.5, 1e-3, 9.8).step == 12);
  CHECK_THAT(rest_departure(lost, 0, 0.5, 1e-3, 9.8).cause, Contains("no longer finite"));
  // 0.79 mm/s, under the speed bound, spreads past 1 mm after 126.6 steps of 0.01 s.
  const Trajectory creep = resting_run(
      300, [](std::int64_t n) { return 0.5 - 7.9e-6 * static_cast<double>(n); },
      [](std::int64_t) { return -7.9e-4; });
  CHECK(stillness_departure(creep, 0, 100, 1e-3, 1e-3).step == 227);
}

TEST_CASE("A drift and a path departure name their first step", "[contact][stack]") {
  const Trajectory run = resting_run(
      100, [](std::int64_t n) { return 0.5 - 1e-4 * static_cast<double>(n); },
      [](std::int64_t) { return 0.0; },
      [](std::int64_t n) { return 1e-4 * static_cast<double>(n); });
  CHECK(drift_departure(run, 0, 1e-3).step == 11);  // 1.1e-3 m across
  const std::vector<double> law(101, 0.5);
  const RestingDeparture d = path_departure(run, 0, law, 5.05e-3);
  CHECK(d.step == 51);
  CHECK_THAT(d.cause, Contains("below its law's height"));
  CHECK(earlier(d, drift_departure(run, 0, 1e-3)).step == 11);
  CHECK(earlier(RestingDeparture{}, d).step == 51);
}

TEST_CASE("A failing landing names its first departure: the rebound before the stillness",
          "[contact][landing]") {
  // Meets the floor (rest height 0.5) at 5 m/s at step 10, leaves at 2.5 m/s and oscillates on:
  // it rebounds at step 11, long before its still window (the last 2 s) starts.
  const Trajectory run = resting_run(
      600,
      [](std::int64_t n) {
        return n <= 10 ? 0.5 + 0.05 * (10 - n) : 0.5 + 0.02 * std::sin(0.3 * (n - 10));
      },
      [](std::int64_t n) { return n <= 10 ? -5.0 : 0.6 * std::cos(0.3 * (n - 10)); });
  LandingSetup setup;
  setup.half_height = 0.5;
  setup.rest_height = 0.5;
  setup.weight = 9.8;
  const LandingObservation seen = observe_landing(run, setup);
  const LandingEnd end = judge_landing_end(run, setup, seen, {0.0, 1e-3, std::nullopt}, {});
  CHECK(end.rebounds);
  CHECK_FALSE(end.settled);
  CHECK(end.departure.step == 11);
  CHECK_THAT(end.departure.sentence(), Contains("(rebound)") && Contains("meeting it at 5 m/s"));
}
