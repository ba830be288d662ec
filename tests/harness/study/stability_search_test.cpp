// Tests harness/study/stability_search.cpp: the bisection on h finds the drag-free spring's edge
// 2/omega (2*sqrt(2)/omega for RK4, none for forward Euler) on every engine; on test doubles with a
// known edge it brackets that edge from above, from below and from a frozen start, stops at the
// cap, and takes the number of probes its doubling and geometric bisection imply; each probe runs
// whole steps over the horizon, thinned to at most 20000 samples.
#include "harness/study/stability_search.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "harness/core/registry.hpp"
#include "harness/oracles/stability_theory.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/faulty_engine.hpp"

using namespace dropcheck;
using testing::extreme_scene;
using testing::registry_factory;

namespace {

// The stiff spring of scenarios/extreme/stiff_spring.toml: w = sqrt(3600/1) = 60 rad/s.
constexpr double kSpringOmega = 60.0;

}  // namespace

TEST_CASE(
    "Stability: bisection finds the drag-free spring's edge h = 2/omega for ours-f64 within 1%",
    "[stability][theory]") {
  const Scene scene = extreme_scene("stiff_spring");
  const StepSearch s =
      search_max_stable_dt(registry_factory("ours-f64"), scene, scene.timestep.seconds);
  const double edge = 2.0 / kSpringOmega;
  // Measured: max_stable_dt 0.033303 (-0.09%), first unstable 0.0333481 (+0.05%), 11 probes.
  CHECK(std::abs(s.max_stable_dt / edge - 1.0) < 0.01);
  CHECK(s.max_stable_dt <= edge);
  CHECK(s.min_unstable_dt >= edge);
  REQUIRE(s.limit.has_value());
  CHECK(*s.limit == FailureMode::unbounded_growth);
  CHECK(theory_max_dt(scene, DampingOrder::AfterForces).value() == Approx(edge).epsilon(1e-12));
}

TEST_CASE(
    "Stability: every engine's bisection finds 2/omega on the drag-free spring, Box2D just below "
    "it",
    "[stability][theory]") {
  // Without damping every law reduces to v' = v - w^2*h*x, x' = x + h*v': stable iff w*h < 2.
  // Measured (10 s horizon, bisection to 0.2%): ours, ours-f64, bullet, ode, mujoco bracket the
  // edge [0.033303, 0.0333481] (MuJoCo fails above it with its own "bad qacc" warning: an engine
  // error); box2d stops at 0.033258 (-0.23%): near the edge the discrete oscillation's speed
  // swells to sqrt(1/(1 - w*h/2)) times the physical one and passes Box2D's 2 m per step limit.
  // An engine that moves the position with the step-start velocity (Chipmunk) is forward Euler
  // on the spring: |z|^2 = 1 + (w*h)^2 at every step, so no step is stable, as the theory says.
  const Scene scene = extreme_scene("stiff_spring");
  const double edge = 2.0 / kSpringOmega;
  for (const std::string& name : available_engine_names()) {
    if (!make_engine(name)->cannot_run(scene).empty()) continue;  // simbody-rkm: springs
    const EngineInfo info = make_engine(name)->info();
    const StepSearch s =
        search_max_stable_dt(registry_factory(name), scene, scene.timestep.seconds);
    INFO(name << ": max_stable_dt " << s.max_stable_dt << ", first unstable " << s.min_unstable_dt);
    if (info.law.scheme == Scheme::RK4) {  // RK4's edge on the imaginary axis: w*h = 2*sqrt(2)
      CHECK(std::abs(s.max_stable_dt / (std::sqrt(2.0) * edge) - 1.0) < 0.01);
      continue;
    }
    if (info.law.position == PositionUpdate::Explicit) {
      CHECK(std::isnan(s.max_stable_dt));
      CHECK(theory_max_dt(scene, info.law).value() == 0.0);
      CHECK(s.limit == FailureMode::unbounded_growth);
      continue;
    }
    CHECK(std::abs(s.max_stable_dt / edge - 1.0) < 0.01);
    if (name != "box2d") CHECK(s.min_unstable_dt >= edge);
    if (name == "box2d") CHECK(s.limit == FailureMode::clamped);
  }
}

namespace {

// Semi-implicit Euler on free fall (exact for the speed: v_n = -g*n*h) with a known stability
// window: below `freeze_below` it holds every body still (frozen, as a sleeping engine), above
// `fail_above` it throws on the first step (an engine error).
class WindowEngine final : public Engine {
 public:
  WindowEngine(double freeze_below, double fail_above)
      : freeze_below_(freeze_below), fail_above_(fail_above) {}
  EngineInfo info() const override {
    EngineInfo i;
    i.name = "window";
    return i;
  }
  void load(const Scene& scene, double h) override {
    g_ = scene.world.gravity;
    h_ = h;
    states_.clear();
    for (const Body& b : scene.bodies) states_.push_back({b.position, b.velocity});
  }
  void set_forces(std::span<const Vec3>) override {}
  void step() override {
    if (h_ > fail_above_) throw EngineError("step too large");
    for (BodyState& s : states_) {
      s.velocity = h_ < freeze_below_ ? Vec3(Vec3::Zero()) : Vec3(s.velocity + g_ * h_);
      s.position += h_ * s.velocity;
    }
  }
  void read(std::span<BodyState> out) const override {
    std::copy(states_.begin(), states_.end(), out.begin());
  }

 private:
  double freeze_below_, fail_above_;
  Vec3 g_ = Vec3::Zero();
  double h_ = 0.0;
  std::vector<BodyState> states_;
};

EngineFactory window(double freeze_below, double fail_above) {
  return [=] { return std::make_unique<WindowEngine>(freeze_below, fail_above); };
}

// A cube falling from 100 m for 1 s: every probe's horizon is the whole second, the cap 1/8 s.
Scene fall() {
  Scene s;
  s.name = "fall";
  s.duration = 1.0;
  s.timestep = {0.01, "0.01"};
  s.world.gravity = Vec3(0.0, -9.8, 0.0);
  Body b;
  b.name = "cube";
  b.position = Vec3(0.0, 100.0, 0.0);
  s.bodies.push_back(b);
  return s;
}

}  // namespace

TEST_CASE("from a stable start the search doubles to the first failure, then bisects to 0.2%",
          "[stability][search]") {
  // h0 = 0.01: 0.02 holds, 0.04 fails (edge 0.037). Geometric bisection of [0.02, 0.04] leaves a
  // ratio 2^(1/2^n): below 1.002 after n = 9 (2^(1/256) = 1.0027, 2^(1/512) = 1.0014): 3 + 9
  // probes.
  const StepSearch s = search_max_stable_dt(window(0.0, 0.037), fall(), 0.01);
  CHECK(s.start == 0.01);
  CHECK(s.horizon == 1.0);
  CHECK(s.cap == 0.125);
  CHECK(s.max_stable_dt <= 0.037);
  CHECK(s.min_unstable_dt > 0.037);
  CHECK(s.min_unstable_dt / s.max_stable_dt - 1.0 <= 2e-3);
  CHECK(s.probes == 12);
  REQUIRE(s.limit.has_value());
  CHECK(*s.limit == FailureMode::engine_error);
  CHECK(std::isnan(s.min_stable_dt));
  // No failure up to the cap: 0.01, 0.02, 0.04, 0.08 and the cap 0.125 itself.
  const StepSearch capped = search_max_stable_dt(window(0.0, 10.0), fall(), 0.01);
  CHECK(capped.max_stable_dt == 0.125);
  CHECK(std::isnan(capped.min_unstable_dt));
  CHECK_FALSE(capped.limit.has_value());
  CHECK(capped.probes == 5);
}

TEST_CASE("from an unstable start the search halves within its step budget, then bisects",
          "[stability][search]") {
  // h0 = 1/8: 1/16 fails, 1/32 holds around the edge 0.037.
  const StepSearch s = search_max_stable_dt(window(0.0, 0.037), fall(), 0.125);
  CHECK(s.max_stable_dt <= 0.037);
  CHECK(s.max_stable_dt >= 0.03125);
  CHECK(s.min_unstable_dt > 0.037);
  CHECK(s.min_unstable_dt <= 0.0625);
  CHECK(s.min_unstable_dt / s.max_stable_dt - 1.0 <= 2e-3);
  // Unstable everywhere: a probe may take 16 times h0's 8 steps, so the halving stops at
  // 1/128 (128 steps); 1/256 would take 256. Five probes: 1/8, 1/16, 1/32, 1/64, 1/128.
  const StepSearch never = search_max_stable_dt(window(0.0, 1e-3), fall(), 0.125);
  CHECK(std::isnan(never.max_stable_dt));
  CHECK(never.min_unstable_dt == 1.0 / 128.0);
  CHECK(never.probes == 5);
  REQUIRE(never.limit.has_value());
  CHECK(*never.limit == FailureMode::engine_error);
}

TEST_CASE("from a frozen start the search finds the smallest stable step, then the largest",
          "[stability][search]") {
  // Held still below 0.003 s (frozen: the fall moves it metres), failing above 0.037 s.
  const StepSearch s = search_max_stable_dt(window(0.003, 0.037), fall(), 0.001);
  CHECK(s.min_stable_dt >= 0.003);
  CHECK(s.min_stable_dt <= 0.003 * 1.002);
  CHECK(s.max_stable_dt <= 0.037);
  CHECK(s.min_unstable_dt > 0.037);
  REQUIRE(s.limit.has_value());
  CHECK(*s.limit == FailureMode::engine_error);
}

TEST_CASE("a probe runs whole steps over its horizon, thinned to at most 20000 samples",
          "[stability][search]") {
  const Scene scene = fall();
  // 0.07/0.01 is 7.000000000000001 in double: still 7 steps, not 8.
  const Scene seven = scene_for_step(scene, 0.01, 0.07);
  CHECK(step_count(seven, 0.01) == 7);
  CHECK(seven.duration == Approx(0.07).epsilon(1e-15));
  CHECK(seven.timestep.seconds == 0.01);
  REQUIRE(seven.timesteps.size() == 1);
  CHECK(seven.timesteps[0].seconds == 0.01);
  CHECK(step_count(scene_for_step(scene, 0.3, 1.0), 0.3) == 4);   // 3.33 steps round up
  CHECK(step_count(scene_for_step(scene, 0.3, 1e-6), 0.3) == 1);  // at least one
  // Every Nth step kept: fewer than 20000 after step 0, with the smallest N that does it.
  for (std::int64_t steps : {1LL, 19999LL, 20000LL, 39999LL, 40000LL, 1234567LL, 20000000LL}) {
    const std::int64_t every = stability_record_every(steps);
    INFO(steps << " steps, every " << every);
    CHECK(steps / every < 20000);
    CHECK((every == 1 || steps / (every - 1) >= 20000));
  }
  // A stack's contact law is judged step by step: every step kept up to 200000 steps.
  Scene stack = load_scene(DROPCHECK_SOURCE_DIR "/scenarios/stack_rest.toml");
  stack.duration = 1000.0;
  CHECK(stability_record_every(stack, 1.0 / 60.0) == 1);    // 60000 steps
  CHECK(stability_record_every(stack, 1.0 / 600.0) == 31);  // 600000 steps: thinned
  CHECK(stability_record_every(scene, 1e-5) == 6);          // no contact law: 100000 steps thinned
}
