// Tests harness/judge/stability_classify.cpp: a stable run, a run's status and speed clamps as
// failures, and every extreme scene on every engine that can run it: a failed run is never called
// stable. A test double (tests/faulty_engine.hpp) places failures where the real engines do not
// have them.
#include "harness/judge/stability_classify.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

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
  // Each scene at its own step, cut to its first 20000 steps (only long_run is longer: the report
  // and `dropcheck stability` run its whole hour) to keep this test short under sanitizers.
  std::vector<std::string> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(DROPCHECK_SOURCE_DIR "/scenarios/extreme"))
    if (entry.path().extension() == ".toml") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 12);
  for (const std::string& file : files) {
    const Scene full = load_scene(file);
    const double h = full.timestep.seconds;
    const Scene scene = scene_for_step(full, h, std::min(full.duration, 20000.0 * h));
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
