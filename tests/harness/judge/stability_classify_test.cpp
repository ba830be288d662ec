// Tests harness/judge/stability_classify.cpp: a run's status and speed clamps as failures, the
// verdict's order (severest first, then by step), the body model the detectors share (body_law)
// and the float spacing they judge by, and every extreme scene on every engine: a failed run is
// never called stable. A test double (tests/faulty_engine.hpp) places failures where the real
// engines do not have them.
#include "harness/judge/stability_classify.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "harness/core/number_format.hpp"
#include "harness/core/registry.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/stability_search.hpp"
#include "tests/faulty_engine.hpp"

using Catch::Matchers::Contains;
using namespace dropcheck;
using testing::classify_faulty;
using testing::engine_available;
using testing::extreme_scene;
using testing::FaultyEngine;

TEST_CASE("Stability: a stable run has no failure", "[stability][classify]") {
  const Scene scene = extreme_scene("stiff_spring");  // w*h = 1.875 at its own step
  auto engine = make_engine("ours-f64");
  const Verdict v =
      classify_run(scene, run_scene(*engine, scene, scene.timestep.seconds), Scalar::f64);
  CHECK(v.stable());
}

TEST_CASE("Stability: a NaN state is classified NaN/Inf and an engine's error as an engine error",
          "[stability][classify]") {
  const Scene scene = extreme_scene("large_step");
  const Verdict nan = classify_faulty(scene, FaultyEngine::Fault::nan, 7);
  REQUIRE_FALSE(nan.stable());
  CHECK(nan.failures.front().mode == FailureMode::non_finite);
  CHECK(nan.failures.front().step == 7);
  CHECK_THAT(nan.failures.front().what, Contains("NaN/Inf") && Contains("step 7"));
  const Verdict error = classify_faulty(scene, FaultyEngine::Fault::error, 3);
  REQUIRE_FALSE(error.stable());
  CHECK(error.failures.front().mode == FailureMode::engine_error);
  CHECK_THAT(error.failures.front().what, Contains("engine error at step 3: solver gave up"));
}

TEST_CASE("Stability: a clamped speed is classified speed clamped", "[stability][classify]") {
  const Scene scene = extreme_scene("huge_gravity");
  const Verdict v = classify_faulty(scene, FaultyEngine::Fault::clamp, 5);
  REQUIRE_FALSE(v.stable());
  CHECK(v.failures.front().mode == FailureMode::clamped);
  CHECK_THAT(v.failures.front().what, Contains("on 26 of 30 steps, first at step 5"));
  if (!engine_available("box2d")) {
    WARN("box2d not compiled in: its real speed clamp is not checked");
    return;
  }
  // Box2D moves a body at most 2 m per step: the 100 g faller passes 120 m/s at step 9 (measured).
  auto engine = make_engine("box2d");
  const Verdict b =
      classify_run(scene, run_scene(*engine, scene, scene.timestep.seconds), Scalar::f32);
  REQUIRE_FALSE(b.stable());
  CHECK(b.failures.front().mode == FailureMode::clamped);
  CHECK(b.failures.front().step == 9);
  CHECK_THAT(b.failures.front().what, Contains("body 'faller' moves 2 m per step (|v| = 120 m/s)"));
}

TEST_CASE(
    "Stability: every extreme scene runs on every engine that can run it without crashing the "
    "harness",
    "[stability][extreme]") {
  // Each scene at its own step, cut to its first 3000 steps. Only long_run is longer (216000 steps:
  // the report and `dropcheck stability` run its whole hour); its first 3000 steps cost this test
  // 4 s, not the 20 s of 20000 (Simbody's allocations under ASan, most of it).
  std::vector<std::string> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(DROPCHECK_SOURCE_DIR "/scenarios/extreme"))
    if (entry.path().extension() == ".toml") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 12);
  for (const std::string& file : files) {
    const Scene full = load_scene(file);
    const double h = full.timestep.seconds;
    const Scene scene = scene_for_step(full, h, std::min(full.duration, 3000.0 * h));
    for (const std::string& name : available_engine_names()) {
      auto engine = make_engine(name);
      if (!engine->cannot_run(scene).empty()) continue;
      INFO(scene.name << " on " << name);
      RunOptions options;
      options.record_every = stability_record_every(step_count(scene, h));
      const Trajectory run = run_scene(*engine, scene, h, options);
      const Verdict v = classify_run(scene, run, engine->info().scalar);
      CHECK((run.status == RunStatus::ok || !v.stable()));  // a failed run is never called stable
      for (const Failure& f : v.failures) CHECK_FALSE(f.what.empty());
    }
  }
}

TEST_CASE("float_spacing is the gap from |x| to the next number above it in the engine's scalar",
          "[stability][classify]") {
  using stability_detail::float_spacing;
  // A float holds 24 significant bits: in [8, 16) numbers lie 2^(3-23) apart, in [4, 8) 2^(2-23).
  // At 8 itself the next float up is 8 + 2^-20 (the one below is 8 - 2^-21).
  CHECK(float_spacing(8.0, Scalar::f32) == std::ldexp(1.0, -20));
  CHECK(float_spacing(-8.0, Scalar::f32) == std::ldexp(1.0, -20));
  CHECK(float_spacing(7.9, Scalar::f32) == std::ldexp(1.0, -21));
  CHECK(float_spacing(10.0, Scalar::f32) == Approx(9.5367431640625e-07).epsilon(1e-15));
  // A double holds 53: 2^-52 at 1, 2^-49 at 8.
  CHECK(float_spacing(1.0, Scalar::f64) == std::ldexp(1.0, -52));
  CHECK(float_spacing(8.0, Scalar::f64) == std::ldexp(1.0, -49));
}

TEST_CASE("body_law adds gravity and constant forces over the mass and combines the springs",
          "[stability][classify]") {
  Scene s;
  s.world.gravity = Vec3(0.0, -9.8, 0.0);
  Body a, b;
  a.name = "a";
  a.mass = 2.0;
  b.name = "b";
  s.bodies = {a, b};
  s.forces.push_back(Force{{0}, ConstantForce{Vec3(2.0, 0.0, 0.0)}});      // 1 m/s^2 along x
  s.forces.push_back(Force{{0, 1}, ConstantForce{Vec3(0.0, 0.0, -4.0)}});  // -2 m/s^2 on a
  s.forces.push_back(Force{{0}, Spring{Vec3(0.0, 0.0, 0.0), 100.0, 1.0, 0.0}});
  s.forces.push_back(Force{{0}, Spring{Vec3(4.0, 0.0, 0.0), 300.0, 2.0, 0.0}});
  s.forces.push_back(Force{{1}, Spring{Vec3(9.0, 9.0, 9.0), 50.0, 0.0, 1.0}});  // only on b
  const stability_detail::BodyLaw la = stability_detail::body_law(s, 0);
  CHECK(la.accel.isApprox(Vec3(1.0, -9.8, -2.0), 1e-15));
  CHECK(la.stiffness == 400.0);
  CHECK(la.dashpot == 3.0);
  // The springs' combined anchor: (100*0 + 300*4)/400 = 3 along x, where their forces cancel.
  CHECK(la.anchor.isApprox(Vec3(3.0, 0.0, 0.0), 1e-15));
  CHECK_FALSE(la.nonlinear);
  const stability_detail::BodyLaw lb = stability_detail::body_law(s, 1);
  CHECK(lb.accel.isApprox(Vec3(0.0, -9.8, -4.0), 1e-15));  // mass 1
  CHECK(lb.nonlinear);
}

TEST_CASE("a verdict lists the severest failure first, then the earliest",
          "[stability][classify]") {
  // A body at rest in empty space, recorded on steps 0..9; the run stopped at step 9 on a NaN and
  // the engine had clamped a speed from step 2: the NaN/Inf (severer) comes first though later.
  Scene scene;
  scene.name = "still";
  scene.duration = 1.0;
  scene.timestep = {0.1, "0.1"};
  Body b;
  b.name = "still";
  scene.bodies.push_back(b);
  Trajectory run;
  run.h = 0.1;
  run.steps = 10;
  run.body_names = {"still"};
  for (std::int64_t n = 0; n < 9; ++n) {
    run.recorded.push_back(n);
    run.states.push_back({Vec3::Zero(), Vec3::Zero()});
  }
  run.status = RunStatus::non_finite;
  run.failed_step = 9;
  run.failure = "NaN/Inf in body 'still' at step 9";
  run.clamped_steps = 3;
  run.first_clamped_step = 2;
  const Verdict v = classify_run(scene, run, Scalar::f64);
  REQUIRE(v.failures.size() == 2);
  CHECK(v.failures[0].mode == FailureMode::non_finite);
  CHECK(v.failures[0].step == 9);
  CHECK(v.failures[1].mode == FailureMode::clamped);
  CHECK(v.failures[1].step == 2);
  CHECK_THAT(v.failures[1].what, Contains("on 3 of 10 steps, first at step 2 (t = 0.2 s)"));
  // A crash counts as an engine error, with the status in its sentence.
  run.status = RunStatus::crashed;
  run.failure = "SIGSEGV";
  const Verdict crash = classify_run(scene, run, Scalar::f64);
  REQUIRE(crash.failures.size() == 2);
  CHECK(crash.failures[0].mode == FailureMode::engine_error);
  CHECK_THAT(crash.failures[0].what,
             Contains(std::string(to_string(RunStatus::crashed)) + ": SIGSEGV"));
}

TEST_CASE("a clamp names the fastest body at the first clamped step with the law's speed there",
          "[stability][classify]") {
  // huge_gravity at 1/60: the faller drops from rest under g = 980 m/s^2 with drag k; its speed
  // after n steps of v = phi*(v + g*h) is g*h*phi*(1 - phi^n)/(1 - phi), 76.9 m/s at step 5, well
  // above the spring's bob (at most w*|g|/w^2 = 16.3 m/s).
  const Scene scene = extreme_scene("huge_gravity");
  const double h = 1.0 / 60.0, phi = std::exp(-scene.world.damping_rate * h);
  const double v5 = 980.0 * h * phi * (1.0 - std::pow(phi, 5)) / (1.0 - phi);
  const Verdict v = classify_faulty(scene, FaultyEngine::Fault::clamp, 5);
  REQUIRE_FALSE(v.stable());
  CHECK(v.failures.front().body == "faller");
  CHECK_THAT(v.failures.front().what,
             Contains("body 'faller' moves " + printf_string("%.3g", v5 * h) +
                      " m per step (|v| = " + printf_string("%.4g", v5) + " m/s)"));
}
