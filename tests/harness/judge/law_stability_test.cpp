// Tests harness/judge/law_stability.cpp: law_instability names where an engine's own law is
// unstable at a step (the spring's edge as omega*h, in closed form with a dashpot; forward Euler
// at every step; RK4's damping edge k*h = 2.785 on drag alone), blew_up tells a blow-up from a
// limit, and judge_while_law_finite judges a run that blew up with its law up to where the law
// left finite values: the blow-up itself is no failure, a departure before it is.
#include "harness/judge/law_stability.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "harness/core/registry.hpp"
#include "harness/oracles/stability_theory.hpp"
#include "harness/run/runner.hpp"
#include "tests/faulty_engine.hpp"

using Catch::Matchers::Contains;
using namespace dropcheck;
using testing::extreme_scene;

namespace {

// A 1 kg body on a spring of w = 60 rad/s with a dashpot C/m = 6 1/s, no drag.
Scene dashpot_spring() {
  Scene s = extreme_scene("stiff_spring");
  std::get<Spring>(s.forces[0].law).damping = 6.0;
  return s;
}

}  // namespace

TEST_CASE("law_instability names omega*h against the spring's closed-form edge with a dashpot",
          "[limits][law_stability]") {
  // Jury's P(-1) > 0 for every semi-implicit order without drag: (w*h)^2 + 2*gamma*h < 4, so
  // w*h < (sqrt(gamma^2 + 4*w^2) - gamma)/w = 1.9025 for gamma = 6, w = 60.
  const double edge = (std::sqrt(36.0 + 4.0 * 3600.0) - 6.0) / 60.0;
  REQUIRE(edge == Approx(1.9025).epsilon(1e-4));
  const Scene scene = dashpot_spring();
  for (DampingOrder order :
       {DampingOrder::AfterForces, DampingOrder::BeforeForces, DampingOrder::AfterPosition}) {
    INFO(law_family_name(order));
    CHECK(law_instability(scene, order, {1.0 / 32.0, "1/32"}).empty());           // w*h = 1.875
    const std::string why = law_instability(scene, order, {1.0 / 30.0, "1/30"});  // w*h = 2
    CHECK_THAT(why, Contains("is unstable at h = 1/30: omega*h = 2 > 1.902, its stability edge; "
                             "with dashpot C/m = 6 1/s, for the spring on 'bob'"));
    CHECK_THAT(why, Contains(law_family_name(order)));
  }
}

TEST_CASE("forward Euler's undamped spring is unstable at every step, RK4's drag past k*h = 2.785",
          "[limits][law_stability]") {
  const Scene spring = extreme_scene("stiff_spring");
  const Law forward(DampingOrder::AfterForces, PositionUpdate::Explicit);
  CHECK_THAT(law_instability(spring, forward, {1.0 / 1000.0, "1/1000"}),
             Contains("omega*h = 0.06, where it is unstable at every step"));
  // RK4 keeps a velocity under drag k only while |1 - u + u^2/2 - u^3/6 + u^4/24| <= 1, u = k*h:
  // u <= 2.7853 (the cubic's root). heavy_drag: k = 60 1/s, no spring.
  const Scene drag = extreme_scene("heavy_drag");
  CHECK(law_instability(drag, kRungeKutta4, {1.0 / 30.0, "1/30"}).empty());  // k*h = 2
  CHECK(law_instability(drag, kRungeKutta4, {2.78 / 60.0, "2.78/60"}).empty());
  CHECK_THAT(law_instability(drag, kRungeKutta4, {2.79 / 60.0, "2.79/60"}),
             Contains("k*h = 2.79 > 2.785") && Contains("for 'dropped'"));
  CHECK_THAT(law_instability(drag, kRungeKutta4, {1.0 / 12.0, "1/12"}), Contains("k*h = 5 > "));
  // Every Euler member damps at any step; an error-controlled scheme has no step bound.
  CHECK(law_instability(drag, DampingOrder::BeforeForces, {1.0, "1"}).empty());
  CHECK(law_instability(spring, kErrorControlled, {1.0, "1"}).empty());
}

TEST_CASE("blew_up is a NaN/Inf, an engine error or a crash, never a limit",
          "[limits][law_stability]") {
  Trajectory t;
  for (RunStatus s : {RunStatus::non_finite, RunStatus::engine_error, RunStatus::crashed}) {
    t.status = s;
    CHECK(blew_up(t));
  }
  for (RunStatus s :
       {RunStatus::ok, RunStatus::refused, RunStatus::timed_out, RunStatus::out_of_memory}) {
    t.status = s;
    CHECK_FALSE(blew_up(t));
  }
}

TEST_CASE("a run that blows up with its law is judged up to where the law stops being finite",
          "[limits][law_stability]") {
  // ours (float) at h = 1/25 on the stiff spring: w*h = 2.4, the step multiplies the amplitude by
  // 3.47, and float overflows within the 250 steps; the law in float overflows with it.
  const Scene scene = extreme_scene("stiff_spring");
  auto engine = make_engine("ours");
  const EngineInfo info = engine->info();
  const Trajectory run = run_scene(*engine, scene, 1.0 / 25.0);
  REQUIRE(blew_up(run));
  const OwnLawVerdict v = judge_while_law_finite(info, scene, run);
  INFO(v.sentence());
  CHECK(v.failure.empty());
  CHECK(v.follows());
  CHECK(v.compared_steps > 20);
  CHECK(v.compared_steps < run.failed_step);
  // The tolerance scales with the largest finite value the law reaches (~1e38 m here), so only a
  // departure of that size shows: the last compared position doubled is one.
  Trajectory moved = run;
  for (std::size_t s = 0; s < moved.samples(); ++s)
    if (moved.recorded[s] == v.compared_steps) moved.states[s].position *= 2.0;
  CHECK_FALSE(judge_while_law_finite(info, scene, moved).follows());
}
