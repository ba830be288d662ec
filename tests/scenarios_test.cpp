// Tests scenarios/: every shipped scene file loads. The directory is globbed at test time, so a
// new scene (in any subdirectory) is covered without editing this file.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "harness/scene/scene_loader.hpp"
#include "tests/shipped_scenes.hpp"

namespace {}  // namespace

TEST_CASE("every scene file shipped in scenarios/ loads without error", "[scenarios][loader]") {
  const std::vector<std::string> files = shipped_scenes();
  REQUIRE(files.size() >= 5);  // the five foundation scenes at least: the glob found the directory
  for (const std::string& file : files) {
    INFO(file);
    std::string error;
    try {
      const dropcheck::Scene s = dropcheck::load_scene(file);
      CHECK_FALSE(s.name.empty());
      CHECK_FALSE(s.bodies.empty());
      CHECK_FALSE(s.timesteps.empty());
    } catch (const dropcheck::InputError& e) {
      error = e.what();
    }
    CHECK(error == "");
  }
}

TEST_CASE("shipped scene names are unique, since tests and reports are keyed by them",
          "[scenarios]") {
  std::map<std::string, std::string> seen;  // name -> first file
  for (const std::string& file : shipped_scenes()) {
    const std::string name = dropcheck::load_scene(file).name;
    INFO(name << " in " << file << " and " << seen[name]);
    CHECK(seen[name].empty());
    seen[name] = file;
  }
}

TEST_CASE(
    "seed_part3.toml is the seed's Part III scene: 1/60 s, g = -9.8, drag 0.98, a static floor",
    "[scenarios]") {
  const dropcheck::Scene s =
      dropcheck::load_scene(DROPCHECK_SOURCE_DIR "/scenarios/seed_part3.toml");
  CHECK(s.timestep.seconds == 1.0 / 60.0);
  CHECK(s.world.gravity == dropcheck::Vec3(0.0, -9.8, 0.0));
  CHECK(std::abs(dropcheck::decay_per_step(s, 1.0 / 60.0) - 0.98) < 1e-15);  // measured 0 (equal)
  CHECK_FALSE(s.world.contacts);  // Part III has no collisions: the cubes fall through the floor
  REQUIRE(s.bodies.size() == 3);
  CHECK(s.bodies[0].is_static);
  CHECK_FALSE(s.bodies[1].is_static);
  CHECK_FALSE(s.bodies[2].is_static);
}
