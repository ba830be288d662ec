// Tests adapters/simbody.cpp: Simbody 3.7 (Debian's build, double) with its fixed-step
// semi-explicit Euler integrator, through the Engine interface, its own traps only: its declared
// laws and drag figure (docs/engines.md sections 2 and 8), its rotational member over Gazebo's
// tumble, and the scenes its damper cannot express. What every engine must do (its own law, a
// force for one step, reload, static bodies) is in tests/adapters/conformance_test.cpp.
#include <catch2/catch.hpp>
#include <string>

#include "adapter_test_support.hpp"
#include "harness/core/registry.hpp"
#include "harness/core/runner.hpp"
#include "harness/oracles/identify_rotation.hpp"
#include "harness/oracles/own_rotation.hpp"

using namespace dropcheck;
using dropcheck::testing::drag_figure_run;
using dropcheck::testing::scenario;

TEST_CASE("Simbody reproduces docs/engines.md's 60-step drag figure", "[simbody][law]") {
  ENGINE_OR_RETURN(engine, "simbody");
  const Trajectory run = drag_figure_run(*engine);
  // Measured 6.5182636233228308 and -5.7366493346810126: Bullet's law (damping before the
  // forces), its position to the bit and its velocity to 4e-15.
  CHECK(run.final_state(0).position.y() == Approx(6.5182636233228308).epsilon(0).margin(1e-12));
  CHECK(run.final_state(0).velocity.y() == Approx(-5.736649334681009).epsilon(0).margin(1e-12));
}

TEST_CASE("Simbody follows explicit/first-order over Gazebo's 10 s tumble, and identify names it",
          "[simbody][rotation]") {
  ENGINE_OR_RETURN(engine, "simbody");
  const Scene scene = scenario("gazebo_boxes_complex");
  const EngineInfo info = engine->info();
  CHECK(info.rotation_law == RotationLaw{Gyroscopic::explicit_term, OrientationUpdate::first_order});
  const Trajectory run = run_scene(*engine, scene, 1e-3);
  REQUIRE(run.status == RunStatus::ok);
  // Measured 8.41e-11 rad and 2.44e-10 rad/s; the nearest other member is 1.17e-4 rad away.
  const RotationResidual own = rotation_residual(
      run, predict_rotation(info.rotation_law, info.law, scene, run.h, run.recorded));
  CHECK(own.angle < 1e-9);
  CHECK(own.w < 1e-8);
  const RotationIdentification id = identify_rotation(scene, run);
  CHECK(id.fits_any);
  CHECK_FALSE(id.ambiguous);
  CHECK(id.fits[id.best].law == info.rotation_law);
  CHECK(id.fits[id.runner_up].max_angle > 1e-5);
}

TEST_CASE("Simbody refuses angular damping on a tumbling body, naming its damper",
          "[simbody][rotation]") {
  ENGINE_OR_RETURN(engine, "simbody");
  CHECK(engine->cannot_run(scenario("spin_drag")).empty());  // about z, a principal axis
  Scene scene = scenario("gazebo_boxes_complex");
  scene.world.angular_damping_rate = 0.5;
  CHECK_THAT(engine->cannot_run(scene), Catch::Contains("torque -c*w per axis"));
}
