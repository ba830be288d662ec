// Tests harness/run/run_limits.cpp: runs refused before they start, with the limit in the message,
// and that a refused run never reaches the engine.
#include "harness/run/run_limits.hpp"

#include <catch2/catch.hpp>

#include "harness/core/registry.hpp"
#include "harness/core/timestep.hpp"
#include "harness/scene/scene_loader.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;

namespace {

// Counts the calls it gets; any call at all means a refused run was started.
class CountingEngine final : public Engine {
 public:
  explicit CountingEngine(Scalar scalar) : scalar_(scalar) {}
  int calls = 0;
  EngineInfo info() const override {
    EngineInfo i;
    i.name = "counting";
    i.scalar = scalar_;
    return i;
  }
  void load(const Scene&, double) override { ++calls; }
  void set_forces(std::span<const Vec3>) override { ++calls; }
  void step() override { ++calls; }
  void read(std::span<BodyState>) const override {}

 private:
  Scalar scalar_;
};

Scene scene_with(const std::string& body, const std::string& world = "",
                 const std::string& head = "duration = 1.0\ntimestep = \"1/10\"\n") {
  return parse_scene(
      head + "[world]\ngravity = [0.0, -9.8, 0.0]\n" + world + "[[body]]\nname = \"cube\"\n" + body,
      "limits.toml");
}

}  // namespace

TEST_CASE("an f32 engine is refused a scene value beyond the float range, an f64 engine is not",
          "[limits]") {
  const Scene s = scene_with("mass = 1e300\nposition = [0.0, 1.7e308, 0.0]\n");
  CountingEngine f32(Scalar::f32), f64(Scalar::f64);
  const Trajectory t = run_scene(f32, s, 0.1, {.isolation = Isolation::in_process});
  CHECK(t.status == RunStatus::refused);
  CHECK(t.failure ==
        "body 'cube' mass = 1e+300 exceeds the float range of counting (f32, largest 3.4e+38)");
  CHECK(t.samples() == 0);
  CHECK(f32.calls == 0);
  CHECK(run_refusal(f64.info(), s, 0.1, {}).empty());
  // Values inside the range pass, however extreme their products inside the engine.
  CHECK(
      run_refusal(f32.info(), scene_with("mass = 3e38\nposition = [0.0, -3e38, 1e-300]\n"), 0.1, {})
          .empty());
  CHECK_THAT(
      run_refusal(f32.info(),
                  scene_with("position = [0.0, 1.0, 0.0]\n", "linear_damping = 1e308\n"), 0.1, {}),
      Contains("world damping rate k = 1e+308 exceeds the float range"));
}

TEST_CASE("every run is held to the step limit, including steps the scene file never named",
          "[limits]") {
  // check runs h/2 and h/4: 1000 s at h = 1/16000 is 1.6e7 steps (allowed), h/4 is 6.4e7 (refused).
  const Scene s =
      scene_with("position = [0.0, 1.0, 0.0]\n", "", "duration = 1000.0\ntimestep = \"1/16000\"\n");
  CountingEngine e(Scalar::f64);
  CHECK(run_refusal(e.info(), s, 1.0 / 16000, {.record_every = 1000}).empty());
  const Trajectory t = run_scene(e, s, 1.0 / 64000, {.record_every = 1000});
  CHECK(t.status == RunStatus::refused);
  CHECK(t.failure == "6.4e+07 steps at h = 1.56e-05 s exceed the limit of " +
                         std::to_string(kMaxSteps) + " steps per run");
  CHECK(e.calls == 0);
}

TEST_CASE(
    "a run whose recorded samples would exceed the memory budget is refused with the estimate",
    "[limits]") {
  // 2e7 steps x 1 body x (48 + 8) bytes = 1.04 GiB: over the 1 GiB budget when every step is kept.
  const Scene s =
      scene_with("position = [0.0, 1.0, 0.0]\n", "", "duration = 2000.0\ntimestep = \"1/10000\"\n");
  CountingEngine e(Scalar::f64);
  const Trajectory t = run_scene(e, s, 1e-4, {.isolation = Isolation::in_process});
  CHECK(t.status == RunStatus::refused);
  CHECK(t.failure ==
        "the recorded trajectory would take 1.04 GiB (2e+07 samples x 1 bodies), over the budget "
        "of 1 "
        "GiB per run; shorten the duration, use a larger step or record fewer steps");
  CHECK(e.calls == 0);
  CHECK(run_refusal(e.info(), s, 1e-4, {.record_every = 2}).empty());  // half the samples fit
  CHECK(recorded_samples(10, 4) == 4);
  CHECK(trajectory_bytes(10, 2) == 10 * (2 * 48 + 8));
  CHECK(trajectory_bytes(10, 2, true) == 10 * (2 * (48 + sizeof(RotationState)) + 8));
}
