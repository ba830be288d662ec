// Tests harness/regression*.cpp: the tiers of the regression guard, the determinism check, and the
// guard at work on a deliberate change to the integrator (tests/harness/moved_drag_engine.hpp).
#include "harness/guard/regression.hpp"

#include <catch2/catch.hpp>
#include <iostream>

#include "../moved_drag_engine.hpp"
#include "../test_dirs.hpp"
#include "contact_bugs.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/registry.hpp"
#include "harness/core/trajectory_hash.hpp"
#include "harness/guard/regression_physics.hpp"
#include "harness/io/trajectory_io.hpp"
#include "harness/run/runner.hpp"
#include "tests/engine_slots.hpp"

using namespace dropcheck;
using namespace dropcheck::testing;

namespace {

// The shipped scenes ours can run (free flight).
const std::vector<std::string> kFreeFlight = {"free_fall", "free_fall_drag", "seed_part3",
                                              "throw_up", "wind"};

}  // namespace

TEST_CASE(
    "Tier 1 passes on identical bits and is skipped, with both builds named, on another build",
    "[regression]") {
  const Baseline now = make_baseline(shipped_scene("throw_up"), testing::factory("ours"));
  CHECK(check_bits(now, now).verdict == TierVerdict::passed);
  Baseline other = now;
  other.build_keys = {"x86_64, Clang 17.0.0, Eigen 3.4.0, glibc 2.36, -O3 -ffp-contract=off"};
  const TierResult r = check_bits(other, now);
  CHECK(r.verdict == TierVerdict::skipped);
  CHECK_THAT(r.message, Catch::Contains("Clang 17.0.0") &&
                            Catch::Contains(now.build_keys.front()) &&
                            Catch::Contains("tier 2 compares at tolerance"));
  other.build_keys.push_back(now.build_keys.front());  // another build gave the same bits too
  CHECK(check_bits(other, now).verdict == TierVerdict::passed);
  other.build_keys.clear();  // a hand-written baseline with no key
  CHECK_THAT(check_bits(other, now).message, Catch::Contains("the baseline names no build"));
  other = now;
  other.hash = "0123456789abcdef";  // same build, different bits
  CHECK(check_bits(other, now).verdict == TierVerdict::failed);
}

TEST_CASE("Tier 2 names scene, engine, body, first differing step, both values and the amount",
          "[regression]") {
  const Baseline expected = make_baseline(shipped_scene("wind"), testing::factory("ours-f64"));
  Baseline now = expected;
  const std::size_t sample = 3, small = 1;  // step 30, body "small"
  now.samples.states[sample * 2 + small].position.y() += 2e-9;
  now.samples.states[5 * 2 + small].position.y() += 5e-9;  // later and larger
  const TierResult r = check_tolerance(expected, now);
  REQUIRE(r.verdict == TierVerdict::failed);
  const double y = expected.samples.at(sample, small).position.y();
  CHECK_THAT(r.message, Catch::StartsWith(
                            "wind / ours-f64 / tolerance: body 'small' first differs at step 30"));
  CHECK_THAT(r.message,
             Catch::Contains("y = " + exact(y) + " in the baseline, " + exact(y + 2e-9) + " now"));
  CHECK_THAT(r.message, Catch::Contains("|dx| = 2e-09 m > 1e-09"));
  CHECK_THAT(r.message, Catch::Contains("max |dx| 5e-09 m (body 'small', step 50)"));
}

TEST_CASE("Tier 2 accepts differences within its tolerance and reports the largest",
          "[regression]") {
  const Baseline expected = make_baseline(shipped_scene("wind"), testing::factory("ours"));
  Baseline now = expected;
  now.samples.states[7].velocity.x() += 0.9e-4;  // f32 tolerance 1e-4 (measured across builds: 0)
  const TierResult r = check_tolerance(expected, now);
  CHECK(r.verdict == TierVerdict::passed);
  CHECK_THAT(r.message,
             Catch::Contains("max |dx| 0 m over 13 samples (tolerance 0.0001 m for f32)"));
  now.sweep[2].analytic_max_dx += 2e-4;  // the error curve moved
  CHECK_THAT(check_tolerance(expected, now).message,
             Catch::Contains("at h = 1/120 max |dx| against the analytic solution moved"));
}

TEST_CASE("Tier 3 passes on ours and ours-f64 for every shipped free-flight scene",
          "[regression]") {
  for (const std::string& stem : kFreeFlight) {
    for (const char* engine : {"ours", "ours-f64"}) {
      const TierResult r =
          check_physics(make_baseline(shipped_scene(stem), testing::factory(engine)));
      INFO(r.message);
      CHECK(r.verdict == TierVerdict::passed);
    }
  }
}

TEST_CASE(
    "Tier 3 fails when the error against the analytic solution stops shrinking at first order",
    "[regression]") {
  Baseline b = make_baseline(shipped_scene("free_fall_drag"), testing::factory("ours-f64"));
  b.sweep[3].analytic_max_dx =
      b.sweep[2].analytic_max_dx * 0.75;  // order 0.415 from 1/120 to 1/240
  const TierResult r = check_physics(b);
  REQUIRE(r.verdict == TierVerdict::failed);
  CHECK_THAT(r.message, Catch::Contains("oracle 1 (analytic solution) fails") &&
                            Catch::Contains("observed 0.415 from h = 1/120 to 1/240"));
}

TEST_CASE("A scene run twice gives identical CSV bytes and hash", "[regression][determinism]") {
  for (const std::string& stem : kFreeFlight) {
    for (const char* engine : {"ours", "ours-f64"}) {
      const Scene scene = shipped_scene(stem);
      const Trajectory a = run_scene(*make_engine(engine), scene, scene.timestep.seconds);
      const Trajectory b = run_scene(*make_engine(engine), scene, scene.timestep.seconds);
      CHECK(trajectories_to_csv({&a, 1}) == trajectories_to_csv({&b, 1}));
      CHECK(trajectory_hash(a) == trajectory_hash(b));
      CHECK(check_determinism(scene, testing::factory(engine)).verdict == TierVerdict::passed);
    }
  }
}

TEST_CASE("The guard catches damping moved after the position update", "[regression][demo]") {
  // What `dropcheck bless` writes for the seed's order, against a fresh run with the drag moved
  // after the position update and the seed's law still declared (moved_drag_engine.hpp). Both sides
  // are doubles, so this test shows the guard at work whatever ours/physics.hpp says today.
  const Baseline expected = make_baseline(shipped_scene("free_fall_drag"), make_seed_order_f64);
  const Baseline now = make_baseline(shipped_scene("free_fall_drag"), make_moved_drag_f64);
  const TierResult bits = check_bits(expected, now), tolerance = check_tolerance(expected, now),
                   physics = check_physics(now);
  std::cout << "What `ctest -L regression` says about the moved damping:\n  " << bits.message
            << "\n  " << tolerance.message << "\n  " << physics.message << "\n";
  CHECK(bits.verdict == TierVerdict::failed);  // same build on both sides
  REQUIRE(tolerance.verdict == TierVerdict::failed);
  // x_1 - x_1' = h^2*g*(1 - f) = 5.4e-5 m after one step; the first sample (step 10) shows 2.82e-3
  // m.
  CHECK_THAT(
      tolerance.message,
      Catch::StartsWith("free_fall_drag / ours-f64 / tolerance: body 'cube' first "
                        "differs at step 10 (samples every 10 steps): y = "
                        "9.8617334079159473 in the baseline, 9.8589116407305539 now, "
                        "|dx| = 0.00282 m > 1e-09 m; max |dx| 0.0696 m (body 'cube', step 60)"));
  REQUIRE(physics.verdict == TierVerdict::failed);
  CHECK_THAT(physics.message,
             Catch::Contains("oracle 2 (own discrete law: v = phi*(v + a*h); x += h*v) fails: at "
                             "h = 1/30 body 'cube' departs from it by 0.141 m"));
  // Where the drag does nothing (f = 1), the change is invisible, and the guard says so.
  const Baseline plain = make_baseline(shipped_scene("free_fall"), make_seed_order_f64);
  CHECK(check_tolerance(plain, make_baseline(shipped_scene("free_fall"), make_moved_drag_f64))
            .verdict == TierVerdict::passed);
}

TEST_CASE("The guard catches a changed quaternion update in ours and blames ours's rotation",
          "[regression][demo][rotation]") {
  // ours-f64 as blessed, against a fresh run whose IntegrateAngularForce turns by the exponential
  // map while its adapter still declares the first-order update (moved_drag_engine.hpp). A spin
  // about a principal axis shows it at once: the first-order update turns by 2*atan(h*w/2) per
  // step, not h*w; positions do not change at all.
  const Scene scene = shipped_scene("gazebo_boxes_simple");
  const Baseline expected = make_baseline(scene, testing::factory("ours-f64"));
  const Baseline now = make_baseline(scene, [] { return std::make_unique<ExpMapOursEngine>(); });
  const TierResult bits = check_bits(expected, now), physics = check_physics(now);
  std::cout << "What `ctest -L regression` says about the changed quaternion update:\n  "
            << bits.message << "\n  " << physics.message << "\n";
  CHECK(bits.verdict == TierVerdict::failed);  // the hash covers the rotation
  REQUIRE(physics.verdict == TierVerdict::failed);
  CHECK_THAT(physics.message,
             Catch::Contains("oracle 2 (own rotational law: ") &&
                 Catch::Contains("the rotation of ours-f64 departs from it by 2.89e-05 rad") &&
                 Catch::Contains("positions and velocities follow") &&
                 Catch::Contains("no-gyro/exp-map or explicit/exp-map"));
}

TEST_CASE("The guard sees contact: friction after the position update and a doubled restitution",
          "[regression][demo][contact]") {
  using dropcheck::testing::buggy_contact_ours;
  using dropcheck::testing::ContactBug;
  const EngineFactory reference = [] { return make_engine("ours-f64"); };
  const auto physics = [&](const char* stem, ContactBug bug) {
    const Scene scene = shipped_scene(stem);
    const EngineFactory engine = buggy_contact_ours(bug);
    return check_physics(make_baseline(scene, engine), nullptr,
                         core_checks(scene, engine, reference), true);
  };
  // The double without a bug is ours' step: the tier passes on both scenes.
  CHECK(physics("slide_stop", ContactBug::none).verdict == TierVerdict::passed);
  CHECK(physics("bounce_e05", ContactBug::none).verdict == TierVerdict::passed);
  CHECK(physics("incline_slide", ContactBug::none).verdict == TierVerdict::passed);
  const TierResult slide = physics("slide_stop", ContactBug::friction_after_position);
  const TierResult bounce = physics("bounce_e05", ContactBug::restitution_twice);
  const TierResult incline = physics("incline_slide", ContactBug::grip_whole_gravity);
  std::cout << "What `ctest -L regression` says about the contact bugs:\n  " << slide.message
            << "\n  " << bounce.message << "\n  " << incline.message << "\n";
  // Each names its first departing step and the neighbouring member it follows instead.
  REQUIRE(slide.verdict == TierVerdict::failed);
  CHECK_THAT(slide.message, Catch::StartsWith("slide_stop / ours-f64 / physics: contact: slide") &&
                                Catch::Contains("DEPARTS at step 1 ") &&
                                Catch::Contains("the friction resolved after the position update"));
  REQUIRE(bounce.verdict == TierVerdict::failed);
  CHECK_THAT(bounce.message,
             Catch::StartsWith("bounce_e05 / ours-f64 / physics: contact: bounce") &&
                 Catch::Contains("DEPARTS at step 28 ") &&
                 Catch::Contains("the restitution applied twice (a rebound of 2e = 1 of"));
  REQUIRE(incline.verdict == TierVerdict::failed);
  CHECK_THAT(incline.message,
             Catch::StartsWith("incline_slide / ours-f64 / physics: contact: slide") &&
                 Catch::Contains("DEPARTS at step 1 ") &&
                 Catch::Contains("the normal force ignores the incline"));
  // The friction-after-position bug in a resting stack: each level rests one step's fall
  // (g*h^2 = 0.0027 m at 1/60) lower than the one under it, and the cause is named.
  const TierResult stack = physics("stack_rest", ContactBug::friction_after_position);
  std::cout << "  " << stack.message << "\n";
  REQUIRE(stack.verdict == TierVerdict::failed);
  CHECK_THAT(stack.message,
             Catch::Contains("(rest height): it rests") &&
                 Catch::Contains("its contact is resolved after the position update"));
}

TEST_CASE("The guard sees a tumbling landing: a turned box's arm forgotten, its turn misplaced",
          "[regression][demo][contact]") {
  using dropcheck::testing::buggy_contact_ours;
  using dropcheck::testing::ContactBug;
  const EngineFactory reference = [] { return make_engine("ours-f64"); };
  const auto physics = [&](ContactBug bug) {
    const Scene scene = shipped_scene("tumble_drop");
    const EngineFactory engine = buggy_contact_ours(bug);
    return check_physics(make_baseline(scene, engine), nullptr,
                         core_checks(scene, engine, reference), true);
  };
  CHECK(physics(ContactBug::none).verdict == TierVerdict::passed);
  const TierResult centre = physics(ContactBug::turned_through_centre);
  const TierResult early = physics(ContactBug::turned_before_contact);
  std::cout << "What `ctest -L regression` says about the tumbling bugs:\n  " << centre.message
            << "\n  " << early.message << "\n";
  // The cube's first corner contact starts step 42 at h = 1/60 (ours-f64): the arm is first
  // missed there, in the angular velocity; the early turn, in the orientation.
  REQUIRE(centre.verdict == TierVerdict::failed);
  CHECK_THAT(centre.message,
             Catch::StartsWith("tumble_drop / ours-f64 / physics: contact: landing") &&
                 Catch::Contains("DEPARTS at step 42: angular velocity off"));
  REQUIRE(early.verdict == TierVerdict::failed);
  CHECK_THAT(early.message, Catch::Contains("DEPARTS at step 42: orientation off"));
}
