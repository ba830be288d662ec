// Tests harness/judge/stability_growth.cpp: unbounded growth of a spring's oscillation energy
// beyond omega*h = 2, of a free flight's speed beyond what any first-order law allows, and of a
// turning body's rotational energy beyond what its angular momentum allows.
#include "harness/judge/stability_growth.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "harness/core/registry.hpp"
#include "harness/judge/stability_classify.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/faulty_engine.hpp"

using Catch::Matchers::Contains;
using namespace dropcheck;
using testing::classify_faulty;
using testing::extreme_scene;
using testing::FaultyEngine;

TEST_CASE("Stability: a spring stepped beyond omega*h = 2 is classified as unbounded growth",
          "[stability][classify]") {
  Scene scene = extreme_scene("stiff_spring");
  const double h = 1.0 / 29.0;  // w*h = 2.069
  auto engine = make_engine("ours-f64");
  const Verdict v = classify_run(scene, run_scene(*engine, scene, h), Scalar::f64);
  REQUIRE_FALSE(v.stable());
  CHECK(v.failures.front().mode == FailureMode::unbounded_growth);
  CHECK_THAT(v.failures.front().what,
             Contains("body 'bob': oscillation energy") && Contains("omega*h = 2.069"));
}

TEST_CASE("Stability: free flight faster than any first-order law allows is unbounded growth",
          "[stability][classify]") {
  const Scene scene = extreme_scene("apex_hang");  // net 1e-4 m/s^2, k = 0.1 1/s: terminal 1e-3 m/s
  const Verdict v = classify_faulty(scene, FaultyEngine::Fault::double_speed, 4);
  REQUIRE_FALSE(v.stable());
  CHECK(v.failures.front().mode == FailureMode::unbounded_growth);
  CHECK(v.failures.front().step == 7);  // ~1e-4 m/s doubled on steps 4..7 passes 1.01e-3 m/s
  CHECK_THAT(v.failures.front().what,
             Contains("body 'hover': speed") && Contains("(|a|/k)*kh/(1 - exp(-kh))"));
}

// Gazebo's tumbling box at h = 0.2 s (|w|*h = 1): the explicit gyroscopic member (ours-f64)
// pumps rotational energy far beyond what its angular momentum allows (|L|^2/(2*I_min) = 41.2 J
// against 8.55 J at the start), the linearly implicit one (ODE) stays within it; Bullet's turn is
// clamped to pi/4 per step (|w|*h = 1), which it reports. Measured with `dropcheck stability
// scenarios/gazebo_boxes_complex.toml`: ours, ours-f64 and MuJoCo stable up to h = 0.1547 s, ODE
// up to the 1 s cap.
TEST_CASE("a turning body whose rotational energy passes what its momentum allows is unstable",
          "[stability][rotation]") {
  Scene scene = load_scene(DROPCHECK_SOURCE_DIR "/scenarios/gazebo_boxes_complex.toml");
  for (const char* name : {"ours-f64", "bullet", "ode"}) {
    const Trajectory run = run_scene(*make_engine(name), scene, 0.2);
    const Verdict v = classify_run(scene, run, Scalar::f64);
    INFO(name << ": " << (v.stable() ? "stable" : v.failures[0].what));
    if (std::string(name) == "ours-f64") {
      // The growth shows steps before the state overflows to Inf/NaN (the severest failure).
      REQUIRE(v.failures.size() == 2);
      CHECK(v.failures[0].mode == FailureMode::non_finite);
      CHECK(v.failures[1].mode == FailureMode::unbounded_growth);
      CHECK(v.failures[1].step < v.failures[0].step);
      CHECK_THAT(v.failures[1].what, Contains("rotational energy") && Contains("exceeds 41.22 J"));
    } else if (std::string(name) == "bullet") {
      REQUIRE(v.failures.size() == 1);
      CHECK(v.failures[0].mode == FailureMode::clamped);
      CHECK_THAT(v.failures[0].what, Contains("turns by |w|*h = 1 rad per step"));
    } else {
      CHECK(v.stable());
    }
  }
}
