// Tests harness/judge/stability_motion.cpp: a body that passes through or sinks into the body it
// started above (tunnelled), and a coordinate held constant while the physics moves it by more
// than half a float spacing and the scene's tolerance (frozen), by rounding or by the engine.
#include "harness/judge/stability_motion.hpp"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "harness/core/registry.hpp"
#include "harness/judge/stability_classify.hpp"
#include "harness/run/runner.hpp"
#include "tests/displaced_run.hpp"
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

namespace {

// A unit cube resting on a static floor 0.01 m thick (top at y = 0), contacts on.
Scene cube_on_floor() {
  Scene s;
  s.name = "rest";
  s.duration = 1.0;
  s.timestep = {0.01, "0.01"};
  s.world.gravity = Vec3(0.0, -9.8, 0.0);
  s.world.contacts = true;
  Body floor;
  floor.name = "floor";
  floor.is_static = true;
  floor.half_extents = Vec3(5.0, 0.005, 5.0);
  floor.position = Vec3(0.0, -0.005, 0.0);
  Body cube;
  cube.name = "cube";
  cube.position = Vec3(0.0, 0.5, 0.0);
  s.bodies = {floor, cube};
  return s;
}

std::vector<Failure> tunnelling(const Scene& scene, const Vec3& cube_moved_by) {
  std::vector<Failure> out;
  stability_detail::find_tunnelling(
      scene, testing::displaced_run(scene, 10, {Vec3::Zero(), cube_moved_by}), out);
  return out;
}

}  // namespace

TEST_CASE("a body sunk deeper than a quarter of the thinner box, or below it, has tunnelled",
          "[stability][motion]") {
  // Resting, the cube's centre is 0.5 + 0.005 above the floor's. It may sink a quarter of the
  // thinner box, 0.5*min(0.5, 0.005) = 0.0025 m (engines rest within millimetres), no more.
  const Scene scene = cube_on_floor();
  CHECK(tunnelling(scene, Vec3::Zero()).empty());
  CHECK(tunnelling(scene, Vec3(0.0, -0.002, 0.0)).empty());
  const std::vector<Failure> sank = tunnelling(scene, Vec3(0.0, -0.003, 0.0));
  REQUIRE(sank.size() == 1);
  CHECK(sank[0].mode == FailureMode::tunnelled);
  CHECK(sank[0].body == "cube");
  CHECK(sank[0].step == 1);
  CHECK_THAT(sank[0].what, Contains("sank 0.003 m into 'floor' (more than a quarter of the "
                                    "thinner box, 0.0025 m)"));
  // Centre 0.1 m below the floor's top: centres -0.095 m apart vertically.
  const std::vector<Failure> below = tunnelling(scene, Vec3(0.0, -0.6, 0.0));
  REQUIRE(below.size() == 1);
  CHECK_THAT(below[0].what, Contains("ended below 'floor'") && Contains("-0.095 m apart"));
  // Off the floor's footprint (|x| = 6 > 0.5 + 5) a body may fall as far as it likes.
  CHECK(tunnelling(scene, Vec3(6.0, -3.0, 0.0)).empty());
}

TEST_CASE("a coordinate is frozen only over 20 steps and beyond the scene's tolerance",
          "[stability][motion]") {
  // A body coasting at 1e-3 m/s along x in empty space (h = 1/60), whose x stays at 0 for the
  // first n steps: the physics moves it 1e-3*n/60 m meanwhile, 3.3e-4 m over 20 steps.
  auto frozen = [](std::int64_t n, double tolerance) {
    Scene s;
    s.name = "coast";
    s.timestep = {1.0 / 60.0, "1/60"};
    s.duration = 1.0;
    s.tolerance = tolerance;
    Body b;
    b.name = "coaster";
    b.velocity = Vec3(1e-3, 0.0, 0.0);
    s.bodies.push_back(b);
    Trajectory t;
    t.h = s.timestep.seconds;
    t.steps = 60;
    t.body_names = {"coaster"};
    for (std::int64_t k = 0; k <= 60; ++k) {
      t.recorded.push_back(k);
      const double x = k <= n ? 0.0 : 1e-3 * static_cast<double>(k) * t.h;
      t.states.push_back({Vec3(x, 0.0, 0.0), Vec3::Zero()});
    }
    std::vector<Failure> out;
    stability_detail::find_frozen(s, t, Scalar::f64, ClassifyOptions{}, out);
    return out;
  };
  const std::vector<Failure> f = frozen(20, 1e-4);
  REQUIRE(f.size() == 1);
  CHECK(f[0].mode == FailureMode::frozen);
  CHECK(f[0].step == 1);
  CHECK_THAT(f[0].what, Contains("frozen at x = 0.000000 from step 1 to step 20") &&
                            Contains("should have moved 0.000333 m") &&
                            Contains("the engine held it"));
  CHECK(frozen(19, 1e-4).empty());  // 19 steps: too short to call
  CHECK(frozen(20, 1e-3).empty());  // 3.3e-4 m is within the scene's tolerance
}
