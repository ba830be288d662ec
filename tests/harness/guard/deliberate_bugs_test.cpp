// The guard sees everything: five deliberate bugs in a copy of ours (deliberate_bugs.hpp), each
// caught by tier 3 on the shipped 3-D throw with the right cause, and each blamed on ours by the
// cross-engine attribution, never on the engine that follows its law. A ctest entry of its own
// (regression.guard_catches_deliberate_bugs, label regression).
#include "deliberate_bugs.hpp"

#include <catch2/catch.hpp>
#include <iostream>

#include "../test_dirs.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/registry.hpp"
#include "harness/guard/baseline.hpp"
#include "harness/guard/baseline_io.hpp"
#include "harness/guard/regression.hpp"
#include "harness/guard/regression_physics.hpp"
#include "harness/study/checks.hpp"
#include "tests/engine_slots.hpp"

using namespace dropcheck;
using namespace dropcheck::testing;
using Catch::Matchers::Contains;

namespace {

struct Case {
  Bug bug;
  const char* name;
  const char* cause;  // what tier 3 must say the run does instead
};

const Case kCases[] = {
    {Bug::z_frozen, "z frozen", "not consistent"},
    {Bug::drag_twice, "drag applied twice", "not consistent"},
    {Bug::gravity_half_step, "gravity at half a step", "not consistent"},
    {Bug::explicit_euler, "explicit Euler",
     "a consistent new scheme: first-order, follows explicit Euler, damping after the forces"},
    {Bug::drag_after_position, "drag after the position update",
     "a consistent new scheme: first-order, follows semi-implicit Euler, damping after the "
     "position update (ODE's order)"},
};

}  // namespace

TEST_CASE("Every deliberate bug in ours is caught by tier 3 with its cause", "[regression][bugs]") {
  const Scene scene = shipped_scene("throw_3d");
  REQUIRE(check_physics(make_baseline(scene, buggy_ours(Bug::none))).verdict ==
          TierVerdict::passed);
  for (const Case& c : kCases) {
    const TierResult r = check_physics(make_baseline(scene, buggy_ours(c.bug)));
    std::cout << c.name << ":\n  " << r.message << "\n";
    INFO(c.name << ": " << r.message);
    CHECK(r.verdict == TierVerdict::failed);
    CHECK_THAT(r.message, Contains("throw_3d / ours / physics: oracle 2 (own discrete law"));
    CHECK_THAT(r.message, Contains(c.cause));
  }
}

TEST_CASE("A consistent new scheme and a broken one get different tier-3 messages",
          "[regression][bugs]") {
  const Scene scene = shipped_scene("free_fall_drag");
  const TierResult twice = check_physics(make_baseline(scene, buggy_ours(Bug::drag_twice)));
  const TierResult euler = check_physics(make_baseline(scene, buggy_ours(Bug::explicit_euler)));
  CHECK_THAT(twice.message, Contains("order 0.0") && Contains("not consistent"));
  CHECK_THAT(euler.message,
             Contains("a consistent new scheme: first-order, follows explicit Euler"));
  CHECK(twice.message != euler.message);
}

TEST_CASE("A consistent new scheme's message says how far it is from the baseline",
          "[regression][bugs]") {
  const Scene scene = shipped_scene("free_fall_drag");
  const Baseline golden =
      read_baseline(std::string(DROPCHECK_SOURCE_DIR) + "/tests/baselines/free_fall_drag.ours.txt");
  const Baseline euler = make_baseline(scene, buggy_ours(Bug::explicit_euler));
  const SampleDiff d = diff_samples(golden.samples, euler.samples, 0.0);
  REQUIRE(d.incomparable.empty());
  REQUIRE(d.max_dx > 1e-4);  // explicit Euler moves the drop measurably
  const TierResult r = check_physics(euler, &golden);
  INFO(r.message);
  CHECK(r.verdict == TierVerdict::failed);
  CHECK_THAT(r.message, Contains("first-order, follows explicit Euler") &&
                            Contains("; differs from the baseline by " + format_length(d.max_dx) +
                                     " at h = " + euler.dt.text));
  CHECK_THAT(check_physics(euler).message, Contains("no baseline to compare with"));
  // A broken scheme is not measured from the baseline: it is not consistent.
  const TierResult twice =
      check_physics(make_baseline(scene, buggy_ours(Bug::drag_twice)), &golden);
  CHECK_THAT(twice.message, Contains("order 0.0") && Contains(": not consistent"));
  CHECK_THAT(twice.message, !Contains("differs from the baseline"));
}

TEST_CASE(
    "The attribution blames ours for every deliberate bug, never the engine that follows its law",
    "[regression][bugs]") {
  const Scene scene = shipped_scene("throw_3d");
  for (const Case& c : kCases) {
    // ours (buggy) against the reference ours-f64 (correct).
    const CheckResult as_engine =
        check_divergence(scene, buggy_ours(c.bug), testing::factory("ours-f64"));
    INFO(c.name << ": " << as_engine.message);
    CHECK_FALSE(as_engine.passed);
    CHECK_THAT(as_engine.message, Contains("UNEXPLAINED") &&
                                      Contains("ours departs from its own law") &&
                                      Contains("ours-f64 follows its own law to 0 m"));
    // A correct engine (ours, f32) against a buggy reference: the reference is blamed.
    const CheckResult as_reference =
        check_divergence(scene, testing::factory("ours"), buggy_ours_f64(c.bug));
    INFO(as_reference.message);
    CHECK_FALSE(as_reference.passed);
    CHECK_THAT(as_reference.message, Contains("ours-f64 departs from its own law") &&
                                         Contains("ours follows its own law to 0 m"));
  }
}

TEST_CASE("Tier 3 asks the measurement core when the stored sweep fails, and no bug gets through",
          "[regression][bugs]") {
  // A limit of the law the stored sweep cannot see: ours's law is unstable at stiff_spring's
  // 1/25 (omega*h = 2.4 > 2), so the run ends in NaN; `dropcheck check` names it a LIMIT.
  const Scene stiff = shipped_scene("extreme/stiff_spring");
  const Baseline b = make_baseline(stiff, testing::factory("ours"));
  const CoreChecks core =
      core_checks(stiff, testing::factory("ours"), testing::factory("ours-f64"));
  CHECK(check_physics(b).verdict == TierVerdict::failed);
  CHECK(!core_checks(stiff, testing::factory("ours"), {}));  // no reference: nothing to ask
  const TierResult r = check_physics(b, nullptr, core);
  INFO(r.message);
  CHECK(r.verdict == TierVerdict::passed);
  CHECK_THAT(r.message, Contains("the checks of `dropcheck check` pass, with LIMITs: own law at "
                                 "h = 1/25: its law (semi-implicit Euler") &&
                            Contains("unstable at h = 1/25: omega*h = 2.4 > 2") &&
                            Contains("(the stored sweep alone fails: the run at h = 1/25 ended"));
  // A broken scheme fails the core too: the tier's own message stands, word for word.
  const Scene scene = shipped_scene("free_fall_drag");
  for (const Bug bug : {Bug::drag_twice, Bug::explicit_euler}) {
    const Baseline broken = make_baseline(scene, buggy_ours(bug));
    const TierResult alone = check_physics(broken);
    const TierResult asked = check_physics(
        broken, nullptr, core_checks(scene, buggy_ours(bug), testing::factory("ours-f64")));
    CHECK(asked.verdict == TierVerdict::failed);
    CHECK(asked.message == alone.message);
  }
}
