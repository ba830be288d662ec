// Tests harness/oracles/identify_rotation.cpp: each double engine's rotational member is named from
// its trajectory alone over Gazebo's tumbling box, and a steady spin, which no gyroscopic term
// touches, is reported as ambiguous rather than named.
#include "harness/oracles/identify_rotation.hpp"

#include <catch2/catch.hpp>

#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"

using namespace dropcheck;

TEST_CASE("identify names each double engine's rotational member from its tumbling trajectory",
          "[identify][rotation]") {
  const Scene scene = load_scene(DROPCHECK_SOURCE_DIR "/scenarios/gazebo_boxes_complex.toml");
  for (const char* name : {"ours-f64", "bullet", "ode", "mujoco"}) {
    auto engine = make_engine(name);
    const EngineInfo info = engine->info();
    const RotationIdentification id =
        identify_rotation(scene, run_scene(*engine, scene, scene.timestep.seconds));
    const RotationFit& best = id.fits[id.best];
    INFO(name << ": best " << rotation_law_key(best.law) << " at " << best.max_angle
              << " rad, runner-up " << id.fits[id.runner_up].max_angle << " rad");
    CHECK(id.fits_any);
    CHECK_FALSE(id.ambiguous);
    CHECK(best.law == info.rotation_law);
    CHECK(id.fits[id.runner_up].max_angle > 1e-4);  // measured >= 1.12e-4 rad for all four
  }
}

TEST_CASE("a spin about a principal axis leaves the gyroscopic members tied: ambiguous",
          "[identify][rotation]") {
  const Scene scene = load_scene(DROPCHECK_SOURCE_DIR "/scenarios/gazebo_boxes_simple.toml");
  auto engine = make_engine("mujoco");
  const RotationIdentification id =
      identify_rotation(scene, run_scene(*engine, scene, scene.timestep.seconds));
  CHECK(id.fits_any);
  CHECK(id.ambiguous);
  CHECK(id.fits[id.best].law.orientation == OrientationUpdate::exponential_map);
}

TEST_CASE("a trajectory without rotation is refused by name", "[identify][rotation]") {
  const Scene scene = load_scene(DROPCHECK_SOURCE_DIR "/scenarios/free_fall.toml");
  const Trajectory run = run_scene(*make_engine("ours-f64"), scene, scene.timestep.seconds);
  CHECK_THROWS_AS(identify_rotation(scene, run), InputError);
}
