// Tests scenarios/friction/ (written by scripts/friction_suite.py): the friction suite's exact
// answers, and ours-f64, whose contact law is the ideal one, passing every check of it. Each
// scene's [expect] figures are checked against the harness by
// tests/scenarios/expectations_test.cpp.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "harness/core/registry.hpp"
#include "harness/oracles/contact_laws.hpp"
#include "harness/scene/scene_files.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/checks.hpp"
#include "tests/engine_slots.hpp"

using namespace dropcheck;

namespace {

const std::string kSuite = DROPCHECK_SOURCE_DIR "/scenarios/friction";

}  // namespace

TEST_CASE("the friction suite: a ramp grid, three stopping distances, sixteen impact phases",
          "[scenarios][friction]") {
  const std::vector<std::string> files = toml_files(kSuite);
  REQUIRE(files.size() == 25 + 3 + 16);
  // Every ramp holds iff tan(theta) <= mu: a slide setup whose pull the grip holds.
  int holding = 0;
  for (const std::string& file : files) {
    if (std::filesystem::path(file).filename().string().rfind("ramp_", 0) != 0) continue;
    const Scene s = load_scene(file);
    const SlideSetup slide = slide_setups(s).at(0);
    const double tan = std::abs(slide.pull) / slide.g;
    const bool holds = slide_to_stop(0.0, slide.mu, slide.g, s.timestep.seconds,
                                     FrictionModel::cone, slide.angle, slide.pull)
                           .stops;
    CHECK(holds == (tan <= slide.mu));
    holding += holds;
  }
  CHECK(holding == 15);  // mu 0.1 holds at 3 degrees only, ..., mu 1.0 at every angle
  // The stops at h = 1/1800, g = 9.81: steps 1835, 918 and 525, each short of v0^2/(2*mu*g) by
  // -0.0545, -0.1090 and -0.1907 % (the clamp law's steps leave out part of the last one).
  const std::pair<const char*, std::pair<std::int64_t, double>> stops[] = {
      {"stop_mu02", {1835, -0.0545}}, {"stop_mu04", {918, -0.1090}}, {"stop_mu07", {525, -0.1907}}};
  for (const auto& [name, figures] : stops) {
    const Scene s = load_scene(kSuite + "/" + name + ".toml");
    const SlideSetup slide = slide_setups(s).at(0);
    const SlideStop law = slide_to_stop(slide.v0, slide.mu, slide.g, s.timestep.seconds,
                                        FrictionModel::cone, slide.angle, slide.pull);
    INFO(name);
    CHECK(law.stop_step == figures.first);
    CHECK(100.0 * (law.step_distance / law.distance - 1.0) == Approx(figures.second).margin(5e-5));
  }
}

TEST_CASE("ours-f64 passes every check of the friction suite", "[scenarios][friction]") {
  for (const std::string& file : toml_files(kSuite)) {
    const Scene scene = load_scene(file);
    for (const CheckResult& r :
         check_scene(scene, testing::factory("ours-f64"), testing::factory("ours-f64"))) {
      INFO(scene.name << ": " << r.check << ": " << r.message);
      CHECK(r.passed);
      CHECK(r.limit.empty());
    }
  }
}
