// Tests harness/study/evaluate.cpp: one scene on several engines over its sweep, each run measured
// against the closed form (first order for semi-implicit Euler), its own law (followed to
// rounding) and, without a closed form, the same engine at the finest step / 8 (the distance the
// law iterated here gives; observed order log2(15/7) for an error C*h); divergences from the
// reference engine, which falls back to the first engine that ran; skipped slots kept in their
// place; the first failed run of a sweep.
#include "harness/study/evaluate.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "harness/core/registry.hpp"
#include "tests/faulty_engine.hpp"

using namespace dropcheck;
using testing::FaultyEngine;
using testing::registry_factory;

namespace {

// A cube thrown up and sideways under gravity and drag k = 0.5 1/s for 1 s, with a sweep.
Scene throw_scene() {
  Scene s;
  s.name = "throw";
  s.duration = 1.0;
  s.timestep = {1.0 / 60.0, "1/60"};
  s.timesteps = {{1.0 / 30.0, "1/30"}, {1.0 / 60.0, "1/60"}, {1.0 / 120.0, "1/120"}};
  s.world.gravity = Vec3(0.0, -9.8, 0.0);
  s.world.damping_rate = 0.5;
  Body b;
  b.name = "cube";
  b.position = Vec3(0.0, 10.0, 0.0);
  b.velocity = Vec3(1.0, 5.0, 0.0);
  s.bodies.push_back(b);
  return s;
}

}  // namespace

TEST_CASE("each engine's sweep is measured against the closed form, its own law and the reference",
          "[evaluate]") {
  const Scene scene = throw_scene();
  const SceneEvaluation se = evaluate_scene(scene, {{"ours-f64", registry_factory("ours-f64"), ""},
                                                    {"ours", registry_factory("ours"), ""}});
  REQUIRE(se.sweep.size() == 3);
  CHECK(se.sweep[0].text == "1/30");
  CHECK(se.default_index == 1);
  CHECK(se.no_analytic.empty());
  CHECK(se.uses_law);
  CHECK_FALSE(se.uses_fine);
  CHECK(se.reference == "ours-f64");
  REQUIRE(se.engines.size() == 2);

  const EngineEvaluation& f64 = se.engines[0];
  REQUIRE(f64.ran());
  REQUIRE(f64.sweep.size() == 3);
  CHECK(&f64.at_default() == &f64.sweep[1]);
  CHECK(f64.first_failure() == nullptr);
  for (const StepEvaluation& s : f64.sweep) {
    INFO("h = " << s.h.text);
    REQUIRE(s.own_law.has_value());
    CHECK(s.own_law->follows());
    REQUIRE(s.vs_law.has_value());
    CHECK(s.vs_law->max_dx <= s.law_budget);
    REQUIRE(s.vs_analytic.has_value());
    CHECK(s.continuous() == &*s.vs_analytic);
    CHECK_FALSE(s.vs_reference.has_value());  // the reference itself
  }
  // Semi-implicit Euler converges at first order to the closed form: the error halves with h.
  REQUIRE(f64.orders_continuous.size() == 2);
  for (double p : f64.orders_continuous) CHECK(p == Approx(1.0).margin(0.05));
  CHECK(f64.orders_reference.empty());

  // ours is the same law in float: its divergence from ours-f64 is rounding, far below the error
  // against the closed form.
  const EngineEvaluation& f32 = se.engines[1];
  for (const StepEvaluation& s : f32.sweep) {
    REQUIRE(s.vs_reference.has_value());
    CHECK(s.vs_reference->max_dx < 1e-4);
    CHECK(s.vs_reference->max_dx < 1e-2 * s.continuous_error());
    REQUIRE(s.reference_by_body.size() == 1);
    CHECK(s.reference_by_body[0].max_dx == s.vs_reference->max_dx);
  }
  CHECK(f32.hash != f64.hash);
}

namespace {

// The largest distance, at the coarse run's steps, between semi-implicit Euler (damping after the
// forces, as ours) on `scene`'s one body at h and at h/m, iterated here: the spring's force
// -S*(|d| - L)*d/|d| from the start of each step, gravity, v = phi*(v + a*h), x += h*v.
double iterated_distance(const Scene& scene, double h, int m) {
  auto run = [&](double step) {
    const Spring& sp = std::get<Spring>(scene.forces[0].law);
    const double phi = std::exp(-scene.world.damping_rate * step);
    Vec3 x = scene.bodies[0].position, v = scene.bodies[0].velocity;
    std::vector<Vec3> out{x};
    for (std::int64_t n = 0; n < step_count(scene, step); ++n) {
      const Vec3 d = x - sp.anchor;
      const Vec3 a =
          scene.world.gravity - sp.stiffness * (d.norm() - sp.rest_length) * d / d.norm();
      v = phi * (v + a * step);
      x += step * v;
      out.push_back(x);
    }
    return out;
  };
  const std::vector<Vec3> coarse = run(h), fine = run(h / m);
  double worst = 0.0;
  for (std::size_t i = 0; i < coarse.size(); ++i)
    worst = std::max(worst, (coarse[i] - fine[i * static_cast<std::size_t>(m)]).norm());
  return worst;
}

}  // namespace

TEST_CASE("without a closed form the sweep is measured against the engine at the finest step / 8",
          "[evaluate]") {
  // A soft spring with a rest length (nonlinear: no closed form), 1 s at 1/60 and 1/120.
  Scene scene = throw_scene();
  scene.world.damping_rate = 0.1;
  scene.timestep = {1.0 / 60.0, "1/60"};
  scene.timesteps = {{1.0 / 60.0, "1/60"}, {1.0 / 120.0, "1/120"}};
  scene.forces.push_back(Force{{0}, Spring{Vec3(0.0, 12.0, 0.0), 2.0, 0.0, 0.5}});
  EvaluateOptions options;
  options.reference = "ode-not-listed";
  const SceneEvaluation se = evaluate_scene(
      scene,
      {{"missing", EngineFactory(), "not compiled in"},
       {"ours-f64", registry_factory("ours-f64"), ""},
       {"faulty", [] { return std::make_unique<FaultyEngine>(FaultyEngine::Fault::error, 80); },
        ""}},
      options);
  CHECK_FALSE(se.no_analytic.empty());
  CHECK(se.uses_fine);
  CHECK(se.fine_step.text == "1/960");
  CHECK(se.fine_step.seconds == Approx(1.0 / 960.0).epsilon(1e-15));
  // The reference asked for did not run: the first engine that did stands in, and it is said.
  CHECK(se.reference == "ours-f64");
  CHECK(se.reference_note == "ode-not-listed did not run this scene (not listed)");
  REQUIRE(se.engines.size() == 3);
  CHECK(se.engines[0].skipped == "not compiled in");

  const EngineEvaluation& ours = se.engines[1];
  for (const StepEvaluation& s : ours.sweep) {
    INFO("h = " << s.h.text);
    CHECK_FALSE(s.vs_analytic.has_value());
    REQUIRE(s.vs_fine.has_value());
    CHECK(s.continuous() == &*s.vs_fine);
    const int m = static_cast<int>(std::lround(s.h.seconds / se.fine_step.seconds));  // 16, 8
    CHECK(s.vs_fine->max_dx == Approx(iterated_distance(scene, s.h.seconds, m)).epsilon(1e-9));
  }
  // Errors C*h against a reference at h_f = 1/960 with error C*h_f, C*(h - h_f), read between
  // 1/60 and 1/120 as the order log2((16 - 1)/(8 - 1)) = log2(15/7) = 1.0995, not 1.
  REQUIRE(ours.orders_continuous.size() == 1);
  CHECK(ours.orders_continuous[0] == Approx(std::log2(15.0 / 7.0)).margin(0.02));

  // The double fails from its 80th step: the 60 steps at 1/60 finish, the 120 at 1/120 do not.
  const EngineEvaluation& faulty = se.engines[2];
  REQUIRE(faulty.ran());
  CHECK(faulty.sweep[0].run.status == RunStatus::ok);
  CHECK(faulty.first_failure() == &faulty.sweep[1]);
  CHECK(faulty.sweep[1].run.status == RunStatus::engine_error);
}
