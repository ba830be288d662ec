// Tests adapters/ode.cpp: ODE 0.16.2 (Debian's double build) through the Engine interface, its own
// traps only: its declared law and drag figure (docs/engines.md section 2), the damping threshold,
// and ODE's error handler. What every engine must do (its own law, a force for one step, reload,
// static bodies, landing) is in tests/adapters/conformance_test.cpp.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "adapter_test_support.hpp"
#include "harness/core/registry.hpp"
#include "harness/run/runner.hpp"

using namespace dropcheck;
using dropcheck::testing::check_bounces;
using dropcheck::testing::drag_figure_run;
using dropcheck::testing::scenario;

namespace {

// A scene ODE must refuse: dBodySetMass checks dMassCheck (mass > 0) in Debian's build.
Scene massless_cube() {
  Scene scene = scenario("free_fall");
  scene.bodies[0].mass = 0.0;  // the loader refuses this; built in code to reach ODE's own check
  return scene;
}

}  // namespace

// Its own law at every step of every shipped scene, and the declaration it is checked against, are
// in tests/adapters/conformance_test.cpp.
TEST_CASE("ODE reproduces docs/engines.md's 60-step drag figure", "[ode][law]") {
  ENGINE_OR_RETURN(engine, "ode");
  const Trajectory run = drag_figure_run(*engine);
  // Measured 6.5182636233228308 exactly (docs/engines.md section 2), Bullet's figure: with v0 = 0
  // damping after the position update gives the same positions as damping before forces.
  CHECK(run.final_state(0).position.y() == Approx(6.5182636233228308).epsilon(0).margin(1e-12));
}

TEST_CASE("ODE damps slow bodies too: the damping threshold is off", "[ode][law]") {
  ENGINE_OR_RETURN(engine, "ode");
  // ODE's default threshold skips damping while |v| <= 0.01 m/s. A body coasting at 5 mm/s with
  // no gravity must still decay by phi = exp(-k*h) every step: v_n = v0*phi^n.
  Scene scene = scenario("throw_up");
  scene.world.gravity = Vec3::Zero();
  scene.bodies[0].velocity = Vec3(0.005, 0.0, 0.0);
  const Trajectory run = run_scene(*engine, scene, 1.0 / 60.0);
  const double phi = std::exp(-scene.world.damping_rate / 60.0);
  // Measured relative error 4.4e-16 after 120 steps (0.005 m/s, undamped, with ODE's default).
  CHECK(run.final_state(0).velocity.x() == Approx(0.005 * std::pow(phi, 120)).epsilon(1e-13));
}

TEST_CASE("An error ODE reports becomes an EngineError and a recorded run status, not an abort",
          "[ode][error]") {
  ENGINE_OR_RETURN(engine, "ode");
  // Debian's ODE keeps its debug checks: dBodySetMass asserts dMassCheck, which fails for m = 0.
  // The handler throws from inside ODE; the throw unwinds through ODE's frames to load().
  CHECK_THROWS_AS(engine->load(massless_cube(), 1.0 / 60.0), EngineError);
  const Trajectory run = run_scene(*engine, massless_cube(), 1.0 / 60.0);
  CHECK(run.status == RunStatus::engine_error);
  CHECK(run.failed_step == 0);  // during load
  CHECK_THAT(run.failure,
             Catch::Contains("ODE internal error") && Catch::Contains("mass must be > 0"));
  // The same engine object is usable again: the half-built world was destroyed with it.
  const Trajectory ok = run_scene(*engine, scenario("free_fall_drag"), 1.0 / 60.0);
  CHECK(ok.status == RunStatus::ok);
  CHECK(ok.final_state(0).position.y() == Approx(6.5182636233228308).epsilon(0).margin(1e-12));
}

TEST_CASE("ODE's bounce follows its law: restitution of the step-start speed, ERP push-out capped",
          "[ode][contact]") {
  ENGINE_OR_RETURN(engine, "ode");
  // Measured over each scene's run at 1/60: 1.0e-9, 2.0e-8 and 7.1e-8 m from the law (its CFM of
  // 1e-10 leaves each rebound about 4e-8 m/s short); the ideal law without the push-out is 1.5 cm
  // away at e = 0.1, where the rebound leaves the sphere in the floor.
  check_bounces(*engine, {{"bounce_e01", 1.0e-9, 0.441, -2.0},
                          {"bounce_e05", 2.0e-8, 2.205, 0.2377777},
                          {"bounce_e09", 7.1e-8, 3.969, 0.8080833}});
  const Scene low = scenario("bounce_e01");
  const BounceVerdict v =
      judge_bounce(run_scene(*engine, low, low.timestep.seconds), bounce_setups(low).at(0),
                   kIdealBounce, low.timestep.seconds);
  CHECK_FALSE(v.follows);
  CHECK(v.worst_gap == Approx(0.0151).epsilon(1e-3));
}
