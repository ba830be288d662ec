// Tests adapters/chipmunk.cpp: Chipmunk 7.0.3 (Debian's double build, 2-D) through the Engine
// interface, its own traps only: its declared law and drag figure (docs/engines.md section 2) and
// the cause named between it and the other engines. What every
// engine must do (its own law, a force for one step, reload, static bodies) is in
// tests/adapters/conformance_test.cpp; its debug banner kept off stdout in tests/CMakeLists.txt.
#include <catch2/catch.hpp>
#include <cstdio>
#include <string>

#include "adapter_test_support.hpp"
#include "harness/core/registry.hpp"
#include "harness/judge/attribution.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/oracles/own_arithmetic.hpp"
#include "harness/oracles/own_rotation.hpp"
#include "harness/run/runner.hpp"

using namespace dropcheck;
using namespace dropcheck::testing;

TEST_CASE("Chipmunk reproduces docs/engines.md's 60-step drag figure", "[chipmunk][law]") {
  ENGINE_OR_RETURN(engine, "chipmunk");
  const Trajectory run = drag_figure_run(*engine);
  // Measured 6.6138744455675145 and -5.736649334681009 (docs/engines.md section 2): the velocity is
  // Bullet's (the same update), the position sums the step-start velocities.
  CHECK(run.final_state(0).position.y() == Approx(6.6138744455675145).epsilon(0).margin(1e-12));
  CHECK(run.final_state(0).velocity.y() == Approx(-5.736649334681009).epsilon(0).margin(1e-12));
}

TEST_CASE("Chipmunk declares before-forces damping with the explicit position update",
          "[chipmunk][law]") {
  ENGINE_OR_RETURN(engine, "chipmunk");
  const EngineInfo info = engine->info();
  CHECK(info.law == Law{DampingOrder::BeforeForces, PositionUpdate::Explicit});
  CHECK(info.scalar == Scalar::f64);
  CHECK(info.capabilities.planar_only);
}

namespace {

// The attribution of `a` against `b` on `scene` at its default step.
Attribution attribute_pair(const std::string& a, const std::string& b, const Scene& scene) {
  auto ea = make_engine(a), eb = make_engine(b);
  const double h = scene.timestep.seconds;
  const EngineInfo ia = ea->info(), ib = eb->info();
  const Trajectory ra = run_scene(*ea, scene, h), rb = run_scene(*eb, scene, h);
  const Trajectory oa = predict_own_arithmetic(ia, scene, h),
                   ob = predict_own_arithmetic(ib, scene, h);
  const Trajectory xa = predict_discrete(ia.law, scene, h), xb = predict_discrete(ib.law, scene, h);
  return attribute({ia, ra, oa, xa}, {ib, rb, ob, xb}, scene.world.damping_rate != 0.0);
}

}  // namespace

TEST_CASE("Between Chipmunk and another engine the cause named is what their laws differ in",
          "[chipmunk][attribution]") {
  ENGINE_OR_RETURN(engine, "chipmunk");
  const Attribution vs_ours = attribute_pair("chipmunk", "ours-f64", scenario("free_fall_drag"));
  CHECK(vs_ours.explained());
  CHECK(vs_ours.law_difference == "damping-order + position-update");
  CHECK_THAT(vs_ours.sentence(), Catch::Contains("(damping order + position update)"));
  // Without damping only the position update separates them.
  const Attribution undamped = attribute_pair("chipmunk", "ours-f64", scenario("free_fall"));
  CHECK(undamped.law_difference == "position-update");
  if (make_engine("bullet")) {
    const Attribution vs_bullet = attribute_pair("chipmunk", "bullet", scenario("free_fall_drag"));
    CHECK(vs_bullet.explained());
    CHECK(vs_bullet.law_difference == "position-update");
  }
}

TEST_CASE("Chipmunk turns by the step-start w and follows its rotational member on the spin",
          "[chipmunk][rotation]") {
  ENGINE_OR_RETURN(engine, "chipmunk");
  const Scene scene = scenario("spin_drag");
  const EngineInfo info = engine->info();
  const Trajectory run = run_scene(*engine, scene, scene.timestep.seconds);
  REQUIRE(run.status == RunStatus::ok);
  REQUIRE(run.rotates);
  // Its own member: measured 4.7e-15 rad over 4 s at h = 1/60 (one space damping, exp(-k_a)).
  const RotationResidual own = rotation_residual(
      run, predict_rotation(info.rotation_law, info.law, scene, run.h, run.recorded));
  CHECK(own.angle < 1e-12);
  CHECK(own.w < 1e-12);
  // The same member turned by the new w instead: the spin decays, so the turn falls short.
  const RotationResidual semi = rotation_residual(
      run,
      predict_rotation(info.rotation_law, DampingOrder::BeforeForces, scene, run.h, run.recorded));
  CHECK(semi.angle > 1e-3);
}

TEST_CASE("Chipmunk refuses a scene that needs two damping rates, naming its one space damping",
          "[chipmunk][rotation]") {
  ENGINE_OR_RETURN(engine, "chipmunk");
  Scene scene = scenario("spin_drag");  // k = 0, k_a = 0.5: runs, nothing moves along a line
  CHECK(engine->cannot_run(scene).empty());
  scene.bodies[0].velocity = Vec3(1.0, 0.0, 0.0);
  CHECK_THAT(engine->cannot_run(scene), Catch::Contains("one space damping"));
  scene.world.damping_rate = scene.world.angular_damping_rate;
  CHECK(engine->cannot_run(scene).empty());
}

TEST_CASE("Chipmunk slides as the replay of its own solver, bit for bit, on every planar slide",
          "[chipmunk][contacts][slide]") {
  check_replayed_slides("chipmunk");
}

TEST_CASE("Chipmunk's slide runs h*v0 past the semi-implicit stop, and 4 steps late at 10 sweeps",
          "[chipmunk][contacts][slide]") {
  const Scene scene = scenario("slide_stop");
  const SlideVerdict v = judged_slide("chipmunk", scene, scene).verdict;
  INFO(v.sentence());
  // The clamp law with Chipmunk's explicit position update stops at step 62 after 2.509472 m
  // (the semi-implicit law's) + h*v0 = 5/60 m: 2.592806 m.
  CHECK(v.clamp_seen.stop_step == 62);
  CHECK(std::abs(v.clamp_seen.distance - (2.509472 + 5.0 / 60.0)) <= 1e-6);
  // Measured: Chipmunk at 10 iterations stops at step 66 after 2.594171 m, at 40 at step 65 after
  // 2.592912 m.
  CHECK(v.seen.stop_step == 66);
  CHECK(v.more_iterations == 40);
  CHECK(v.more_seen.stop_step == 65);
  CHECK(std::abs(v.more_seen.distance - v.clamp_seen.distance) <= 2e-4);
}

TEST_CASE("Chipmunk's product rule left unmapped departs from the replay",
          "[chipmunk][contacts][slide]") {
  // Each shape given mu itself instead of sqrt(mu): the pair gets mu^2.
  const SlideVerdict u = slide_with_materials("chipmunk", [](const Body&) { return 0.5; });
  INFO(u.sentence());
  CHECK_FALSE(u.follows);
}

TEST_CASE("A cube dropped on a floor lands on time and rests a slop deep in Chipmunk",
          "[chipmunk][contacts]") {
  const auto [info, h, t_c, l] = land_drop_on_floor(*required_engine("chipmunk"), 1e-4);
  // Chipmunk moves the body before it collides, so the velocity answers a step after the one that
  // ends in the floor: measured 2.46 steps after t_c (the check's first contact is the law's).
  CHECK(std::abs(static_cast<double>(l.response_step) * h - t_c) <= 3 * h);
  CHECK(std::abs(l.rest - 0.5 - info.rest_offset) <= info.rest_tolerance);
  CHECK(l.settled_at <= 3.0);
}

TEST_CASE("Chipmunk bounces as the replay of its own solver, bit for bit, on every bounce scene",
          "[chipmunk][contacts][bounce]") {
  // Measured: at e = 0.9 the apexes are 0.8097, 0.6536, 0.5287 m (the ideal law's 0.8081, 0.6469,
  // 0.5215 m); at e = 0.1 the ball never rises above the floor's top: the bias impulse pushes it
  // back out of its penetration beyond the slop.
  check_replayed_bounces("chipmunk");
}

TEST_CASE("Chipmunk moves as its replay, bit for bit, in random contact scenes",
          "[chipmunk][contacts][replay]") {
  // Thrown boxes and balls with any friction and restitution at 1/30, 1/60 and 1/240.
  check_replay_on_random_scenes("chipmunk", 40);
}
