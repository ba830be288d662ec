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
using dropcheck::testing::drag_figure_run;
using dropcheck::testing::scenario;

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
