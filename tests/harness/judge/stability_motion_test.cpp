// Tests harness/judge/stability_motion.cpp: a body that passes through the thin floor (tunnelled),
// and a coordinate held constant by float rounding or by the engine (frozen).
#include "harness/judge/stability_motion.hpp"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "harness/core/registry.hpp"
#include "harness/judge/stability_classify.hpp"
#include "harness/run/runner.hpp"
#include "tests/faulty_engine.hpp"

using Catch::Matchers::Contains;
using namespace dropcheck;
using testing::classify_faulty;
using testing::engine_available;
using testing::extreme_scene;
using testing::FaultyEngine;

TEST_CASE("Stability: float positions at the tiny step are classified frozen, double ones move",
          "[stability][classify]") {
  const Scene scene = extreme_scene("tiny_step");
  auto f32 = make_engine("ours");
  const Verdict v =
      classify_run(scene, run_scene(*f32, scene, scene.timestep.seconds), Scalar::f32);
  REQUIRE(v.failures.size() == 1);  // near_0 moves: float spacing at 0.01 m is 9.3e-10 m
  const Failure& f = v.failures.front();
  CHECK(f.mode == FailureMode::frozen);
  CHECK(f.body == "at_10m");
  CHECK(f.step == 1);
  CHECK_THAT(f.what, Contains("frozen at y = 10.000000 from step 1 to step 200") &&
                         Contains("v*h = 9.8e-10 m to 2e-07 m per step is below half the float "
                                  "spacing 4.8e-07 m at 10 m"));
  auto f64 = make_engine("ours-f64");
  CHECK(classify_run(scene, run_scene(*f64, scene, scene.timestep.seconds), Scalar::f64).stable());
}

TEST_CASE("Stability: a body an engine stops (sleeping) is frozen, held by the engine",
          "[stability][classify]") {
  const Scene scene = extreme_scene("near_zero");  // |v| ~ 1e-6 m/s: below every sleeping threshold
  const Verdict v = classify_faulty(scene, FaultyEngine::Fault::stop, 100);
  REQUIRE_FALSE(v.stable());
  CHECK(v.failures.front().mode == FailureMode::frozen);
  CHECK(v.failures.front().step == 100);
  CHECK_THAT(v.failures.front().what, Contains("the engine held it"));
}

TEST_CASE("Stability: a body that passes through the thin floor is classified tunnelled",
          "[stability][classify]") {
  const Scene scene = extreme_scene("thin_floor");
  const Verdict v =
      classify_faulty(scene, FaultyEngine::Fault::none, 0);  // claims contacts, has none
  REQUIRE_FALSE(v.stable());
  CHECK(v.failures.front().mode == FailureMode::tunnelled);
  CHECK(v.failures.front().step == 1);
  CHECK_THAT(v.failures.front().what, Contains("body 'bullet' ended below 'floor'") &&
                                          Contains("static") && Contains("3.34 m per step"));
  // Real engines with discrete collision (measured at 1/60: bullet, ode and mujoco tunnel; box2d's
  // continuous collision stops the cube on the floor).
  for (const char* name : {"bullet", "ode", "mujoco"}) {
    if (!engine_available(name)) continue;
    auto engine = make_engine(name);
    const Verdict r = classify_run(scene, run_scene(*engine, scene, scene.timestep.seconds),
                                   engine->info().scalar);
    INFO(name);
    REQUIRE_FALSE(r.stable());
    CHECK(r.failures.front().mode == FailureMode::tunnelled);
  }
}
