// Tests harness/judge/stack_verdict.cpp: a stack is held to its engine's stack law; a sink beyond
// it, a drift or a jitter fails, naming the body and the quantity; a load the solver's sweeps
// cannot hold is a named limit. The runs are written here, so no engine is needed.
#include "harness/judge/stack_verdict.hpp"

#include <catch2/catch.hpp>

#include "harness/scene/scene_loader.hpp"
#include "tests/displaced_run.hpp"
#include "tests/shipped_scenes.hpp"

using namespace dropcheck;
using Catch::Contains;

namespace {

// Every body still, body `moved` displaced by `by` from step `from` on.
Trajectory still_run(const Scene& scene, std::int64_t steps, std::size_t moved = 0,
                     Vec3 by = Vec3::Zero(), std::int64_t from = 0) {
  std::vector<Vec3> each(scene.bodies.size(), Vec3::Zero());
  each[moved] = by;
  return testing::displaced_run(scene, steps, each, from);
}

}  // namespace

TEST_CASE("a stack that sinks as its law says holds; more, a drift or a jitter fails",
          "[contact][stack]") {
  const Scene scene = testing::shipped("stack_rest");
  const StackSetup s = stack_setups(scene).at(0);
  const double h = scene.timestep.seconds;
  const std::int64_t steps = 300;
  EngineInfo ode;
  ode.stack_law = {.compliance = 1e-10 / 0.2, .points = 4, .sink_bound = 1e-12};
  // The stack as its law says: the medium cube 4.083e-11 m down, the small one 6.125e-11 m.
  std::vector<Vec3> law(scene.bodies.size(), Vec3::Zero());
  for (std::size_t k = 0; k < 2; ++k)
    law[s.levels[k].body].y() = -predict_stack(s, k, ode, h, steps).sink;
  CHECK(law[2].y() == Approx(-6.125e-11).epsilon(1e-3));
  for (const StackBodyVerdict& v :
       judge_stack(testing::displaced_run(scene, steps, law), s, ode, h)) {
    CHECK(v.holds());
    CHECK_FALSE(v.unheld);
  }
  // Rigid, not sinking at all: below 0.8 of the law (its bound, 1e-12 m, is rounding).
  CHECK_FALSE(judge_stack(still_run(scene, steps), s, ode, h)[0].holds());
  // The small cube (body 2) 1e-6 m lower: far beyond its law's 6.1e-11 m.
  std::vector<Vec3> deeper = law;
  deeper[2].y() = -1e-6;
  const auto sunk = judge_stack(testing::displaced_run(scene, steps, deeper), s, ode, h);
  CHECK(sunk[0].holds());
  CHECK_FALSE(sunk[1].holds());
  CHECK_THAT(sunk[1].sentence(), Contains("(level 2) sinks 1e-06 m") && Contains("OUT OF BOUNDS") &&
                                     Contains("first departs at step 1 (rest height)") &&
                                     Contains("a soft contact's sag"));
  // A soft contact that does not sink at all fails too: MuJoCo's law puts the 1 kg cube under
  // 1e5 kg 8.507e-3 m down at 1/60, and a run that stays at the geometry is 100 % short.
  const Scene ratio = testing::shipped("extreme/mass_ratio");
  EngineInfo soft;
  soft.stack_law = {.soft = 1e-4 * 1.25 / 16.0, .tau_steps = 2.0, .sink_bound = 1e-12};
  const auto unsunk = judge_stack(still_run(ratio, 300), stack_setups(ratio).at(1), soft, h);
  CHECK(unsunk[0].predicted.sink == Approx(8.507e-3).epsilon(1e-3));
  CHECK_FALSE(unsunk[0].holds());
  // Slid 2 mm aside: beyond the 1 mm drift bound; and the jump at step 250 is in the still window.
  const auto slid = judge_stack(still_run(scene, steps, 1, {0.002, 0.0, 0.0}, 250), s, ode, h);
  CHECK_FALSE(slid[0].holds());
  CHECK_THAT(slid[0].sentence(), Contains("drift 0.002 m TOO FAR") && Contains("NOT STILL") &&
                                     Contains("first departs at step 0 (rest height): it "
                                              "rests 4.08e-11 m above"));
  // Its drift alone: a step of 2 mm at step 250.
  CHECK(drift_departure(still_run(scene, steps, 1, {0.002, 0.0, 0.0}, 250), s.levels[0].body, 1e-3)
            .step == 250);
}

TEST_CASE("a load an iterative solver cannot hold is a limit for the whole column",
          "[contact][stack]") {
  const Scene scene = testing::shipped("extreme/mass_ratio");
  const StackSetup s = stack_setups(scene).at(0);  // 1000 kg on 1 kg
  EngineInfo gs;
  gs.stack_law = {.iterations = 10};
  // The light cube (body 1) squeezed 1 m aside: the limit covers it, though its own contact
  // (with the floor) has nothing to sweep against.
  const auto v =
      judge_stack(still_run(scene, 300, 1, {1.0, 0.0, 0.0}, 1), s, gs, scene.timestep.seconds);
  CHECK_FALSE(v[0].holds());
  CHECK(v[0].unheld);
  CHECK(v[0].passes());
  CHECK_THAT(v[0].limit_text(),
             Contains("each sweep leaves 0.999 of the error between 1 kg and the "
                      "1000 kg on it, 0.99 after a step's sweeps"));
  // Stillness needs 2 s after the column's last landing: the heavy cube drops 1 m (0.4518 s), so
  // a 2.4 s run cannot show it.
  CHECK(v[0].still_judged);
  const auto short_run = judge_stack(still_run(scene, 144), s, gs, scene.timestep.seconds);
  CHECK_FALSE(short_run[1].still_judged);
  CHECK_THAT(short_run[1].sentence(), Contains("stillness not judged"));
  // The limit waives the bounds, not the floor: a light cube pushed through it fails.
  const auto through =
      judge_stack(still_run(scene, 300, 1, {0.0, -1.0, 0.0}, 1), s, gs, scene.timestep.seconds);
  CHECK(through[0].unheld);
  CHECK_FALSE(through[0].above_floor);
  CHECK_FALSE(through[0].passes());
  // A converging solver gets no limit: the same run fails.
  EngineInfo direct;
  const auto w =
      judge_stack(still_run(scene, 300, 1, {1.0, 0.0, 0.0}, 1), s, direct, scene.timestep.seconds);
  CHECK_FALSE(w[0].passes());
}
