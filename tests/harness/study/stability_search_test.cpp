// Tests harness/study/stability_search.cpp: the bisection on h finds the drag-free spring's edge
// 2/omega (2*sqrt(2)/omega for RK4, none for forward Euler) on every engine.
#include "harness/study/stability_search.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "harness/core/registry.hpp"
#include "harness/oracles/stability_theory.hpp"
#include "tests/faulty_engine.hpp"

using namespace dropcheck;
using testing::extreme_scene;
using testing::registry_factory;

namespace {

// The stiff spring of scenarios/extreme/stiff_spring.toml: w = sqrt(3600/1) = 60 rad/s.
constexpr double kOmega = 60.0;

}  // namespace

TEST_CASE(
    "Stability: bisection finds the drag-free spring's edge h = 2/omega for ours-f64 within 1%",
    "[stability][theory]") {
  const Scene scene = extreme_scene("stiff_spring");
  const StepSearch s =
      search_max_stable_dt(registry_factory("ours-f64"), scene, scene.timestep.seconds);
  const double edge = 2.0 / kOmega;
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
  const double edge = 2.0 / kOmega;
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
