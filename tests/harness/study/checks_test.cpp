// Tests harness/study/checks.cpp: the checks pass on correct engines and catch broken mappings
// with a message that names the scene, engine, body, step and both values.
#include "harness/study/checks.hpp"

#include <catch2/catch.hpp>

#include "harness/core/registry.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/engine_slots.hpp"

using namespace dropcheck;

namespace {

// Wraps ours-f64 and breaks one thing, as an adapter bug would.
class BrokenEngine final : public Engine {
 public:
  enum class Bug { wrong_law, default_gravity, per_second_drag };
  explicit BrokenEngine(Bug bug) : bug_(bug), inner_(make_engine("ours-f64")) {}

  EngineInfo info() const override {
    EngineInfo i = inner_->info();
    i.name = "broken";
    if (bug_ == Bug::wrong_law) i.law = DampingOrder::BeforeForces;  // claims Bullet's order
    return i;
  }
  void load(const Scene& scene, double h) override {
    Scene s = scene;
    if (bug_ == Bug::default_gravity) s.world.gravity = Vec3(0, -10, 0);  // Bullet's silent default
    // Drag given per second where the engine wants per step: phi = exp(-k) instead of exp(-k*h).
    if (bug_ == Bug::per_second_drag) s.world.damping_rate *= 1.0 / h;
    inner_->load(s, h);
  }
  void set_forces(std::span<const Vec3> f) override { inner_->set_forces(f); }
  void step() override { inner_->step(); }
  void read(std::span<BodyState> out) const override { inner_->read(out); }

 private:
  Bug bug_;
  std::unique_ptr<Engine> inner_;
};

EngineFactory broken(BrokenEngine::Bug bug) {
  return [bug] { return std::make_unique<BrokenEngine>(bug); };
}

}  // namespace

TEST_CASE("every check passes for ours and ours-f64 on the drag scene", "[checks]") {
  const Scene scene = load_scene("scenarios/free_fall_drag.toml");
  for (const char* name : {"ours", "ours-f64"}) {
    const auto results = check_scene(scene, testing::factory(name), testing::factory("ours-f64"));
    REQUIRE(results.size() == 4);  // own law at three steps + divergence/convergence
    for (const CheckResult& r : results) {
      INFO(r.check << ": " << r.message);
      CHECK(r.passed);
    }
  }
}

TEST_CASE("the own-law check runs at the scene's step and two others", "[checks]") {
  const auto steps = conformance_steps(load_scene("scenarios/wind.toml"));
  REQUIRE(steps.size() == 3);
  CHECK(steps[0].text == "1/60");
  CHECK(steps[1].text == "1/30");
  CHECK(steps[2].text == "1/120");
}

TEST_CASE("an adapter that declares the wrong law fails its own-law check with both values",
          "[checks]") {
  const Scene scene = load_scene("scenarios/free_fall_drag.toml");
  const CheckResult r = check_own_law(scene, broken(BrokenEngine::Bug::wrong_law), scene.timestep);
  CHECK_FALSE(r.passed);
  CHECK(r.engine == "broken");
  CHECK(r.scene == "free_fall_drag");
  CHECK_THAT(r.message, Catch::Contains("body 'cube' step"));
  CHECK_THAT(r.message, Catch::Contains("engine x = ("));
  CHECK_THAT(r.message, Catch::Contains("law x = ("));
}

TEST_CASE("an adapter that keeps a default gravity is caught as an unexplained residual",
          "[checks]") {
  const Scene scene = load_scene("scenarios/free_fall.toml");
  CHECK_FALSE(
      check_own_law(scene, broken(BrokenEngine::Bug::default_gravity), scene.timestep).passed);
  const CheckResult r = check_divergence(scene, broken(BrokenEngine::Bug::default_gravity),
                                         testing::factory("ours-f64"));
  CHECK_FALSE(r.passed);
  CHECK_THAT(r.message, Catch::Contains("UNEXPLAINED residual"));
}

TEST_CASE("drag mapped per second instead of per step is caught by the own-law check", "[checks]") {
  const Scene scene = load_scene("scenarios/throw_up.toml");
  const CheckResult r =
      check_own_law(scene, broken(BrokenEngine::Bug::per_second_drag), scene.timestep);
  CHECK_FALSE(r.passed);
  CHECK_THAT(r.message, Catch::Contains("worst at body 'cube'"));
}
