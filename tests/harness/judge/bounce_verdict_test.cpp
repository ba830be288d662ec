// Tests harness/judge/bounce_verdict.cpp: a run is judged step by step against its engine's
// bounce law; the members that move that law off the ideal one are named; a run that follows the
// ideal law where its engine declares another, or that gains height, is caught. The runs are the
// laws themselves, written as trajectories, so no engine is needed; the last test runs ours (f32),
// whose path parts from its law's where a contact is decided within rounding of the floor.
#include "harness/judge/bounce_verdict.hpp"

#include <catch2/catch.hpp>

#include "harness/core/registry.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/shipped_scenes.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;

namespace {

constexpr BounceLaw kOde{.erp = 0.2, .max_push = 0.3};

// `law`'s path on the scene's bounce as a trajectory, every step recorded (the floor at rest).
Trajectory law_run(const Scene& scene, const BounceSetup& s, const BounceLaw& law) {
  const double h = scene.timestep.seconds;
  Trajectory t;
  t.h = h;
  t.steps = step_count(scene, h);
  for (const Body& body : scene.bodies) t.body_names.push_back(body.name);
  const BouncePath p = bounce_path(law, s.h0, s.e, s.g, h, t.steps);
  for (std::int64_t n = 0; n <= t.steps; ++n) {
    t.recorded.push_back(n);
    const auto i = static_cast<std::size_t>(n);
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
      t.states.push_back(b == s.body ? BodyState{Vec3(0.0, p.gap[i] + s.radius + s.floor_top, 0.0),
                                                 Vec3(0.0, p.v[i], 0.0)}
                                     : BodyState{scene.bodies[b].position, {}});
  }
  return t;
}

}  // namespace

TEST_CASE("a bounce following its engine's law passes, with the members that move it named",
          "[contact][bounce]") {
  const Scene scene = testing::shipped("bounce_e01");
  const std::vector<BounceSetup> setups = bounce_setups(scene);
  REQUIRE(setups.size() == 1);
  CHECK(setups[0].h0 == 1.0);
  CHECK(setups[0].e == 0.1);
  const double h = scene.timestep.seconds;
  const BounceVerdict ode = judge_bounce(law_run(scene, setups[0], kOde), setups[0], kOde, h);
  CHECK(ode.follows);
  CHECK(ode.worst_gap < 1e-15);  // the written heights round once
  CHECK(ode.seen.contact_step == 27);
  // The ideal law stays 0.01512 m in the floor; the push-out brings the sphere back to the surface.
  CHECK(ode.law_to_ideal == Approx(0.0151).epsilon(1e-3));
  REQUIRE(ode.causes.size() == 1);
  CHECK_THAT(ode.causes[0], Contains("push-out 0.2*depth/h capped at 0.3 m/s"));
  CHECK_THAT(ode.sentence(), Contains("the same path to") && Contains("0.0151 m off the ideal"));
}

TEST_CASE("a bounce that follows the ideal law where its engine declares a push-out departs",
          "[contact][bounce]") {
  const Scene scene = testing::shipped("bounce_e01");
  const BounceSetup s = bounce_setups(scene)[0];
  const double h = scene.timestep.seconds;
  const BounceVerdict v = judge_bounce(law_run(scene, s, kIdealBounce), s, kOde, h);
  CHECK_FALSE(v.follows);
  CHECK(v.follows_ideal);
  CHECK(v.worst_gap == Approx(0.0151).epsilon(1e-3));
  // The first step over the path tolerance is named first, then the largest gap and its step:
  // the ideal law stays in the floor after the contact step (27), where ODE's pushes it out a
  // fifth of the depth a step; the paths are 1e-6 m apart by step 30.
  CHECK(v.first_step == 30);
  CHECK(v.first_step <= v.worst_step);
  CHECK_THAT(v.sentence(), Contains("DEPARTS at step 30 (first over 1e-06 m; the largest gap ") &&
                               Contains("follows the ideal law ("));
  // A threshold above the impact speed: the rebound never happens, the departure is named.
  const BounceVerdict dead =
      judge_bounce(law_run(scene, s, {.threshold = 5.0}), s, kIdealBounce, h);
  CHECK_FALSE(dead.follows);
}

TEST_CASE("a bounce that climbs above where it fell from is flagged: energy rises",
          "[contact][bounce]") {
  const Scene scene = testing::shipped("bounce_e09");
  const BounceSetup s = bounce_setups(scene)[0];
  const double h = scene.timestep.seconds;
  // The law of e = 0.9 judged as e = 0.9 passes, apexes falling (0.8081, 0.6469, 0.5215 m).
  const BounceVerdict fair = judge_bounce(law_run(scene, s, kIdealBounce), s, kIdealBounce, h);
  CHECK(fair.follows);
  CHECK_FALSE(fair.energy_rises);
  REQUIRE(fair.seen.apexes.size() == 3);
  CHECK(fair.seen.apexes[0] == Approx(0.8081).epsilon(1e-4));
  // A run that returns more than it received (e = 1.2, the scene says 0.9).
  BounceSetup gains = s;
  gains.e = 1.2;
  const BounceVerdict v = judge_bounce(law_run(scene, gains, kIdealBounce), s, kIdealBounce, h);
  CHECK(v.energy_rises);
  CHECK_FALSE(v.follows);
  CHECK_THAT(v.sentence(), Contains("ENERGY RISES"));
}

TEST_CASE(
    "a float run that parts from its law's path names the step whose contact it decides "
    "on the other side",
    "[contact][bounce]") {
  const Scene scene = testing::shipped("bounce_e05");
  const BounceSetup s = bounce_setups(scene).at(0);
  std::unique_ptr<Engine> ours = make_engine("ours");
  const double h = scene.timestep.seconds;
  const BounceVerdict v = judge_bounce(run_scene(*ours, scene, h), s, ours->info().bounce_law, h);
  INFO(v.sentence());
  CHECK(v.follows);
  REQUIRE(v.step_gap >= 0.0);  // its path parts from the law's in double
  REQUIRE(v.decided_step >= 0);
  // One of the two starts that step in the floor (or touching it), the other above it.
  CHECK((v.law_gap_there <= 0.0) != (v.run_gap_there <= 0.0));
  CHECK_THAT(v.sentence(), Contains("decide its contact on either side"));
}

TEST_CASE("a bounce whose run skipped steps is not judged, whatever its engine's solver",
          "[contact][bounce]") {
  // Every bounce law is a path step by step: samples every other step cannot be laid beside it.
  const Scene scene = testing::shipped("bounce_e05");
  const BounceSetup s = bounce_setups(scene).at(0);
  const double h = scene.timestep.seconds;
  Trajectory run = law_run(scene, s, kOde);
  Trajectory sparse = run;
  sparse.recorded.clear();
  sparse.states.clear();
  for (std::size_t i = 0; i < run.recorded.size(); i += 2) {
    sparse.recorded.push_back(run.recorded[i]);
    for (std::size_t b = 0; b < run.bodies(); ++b) sparse.states.push_back(run.at(i, b));
  }
  EngineInfo exact;
  exact.bounce_law = kOde;
  EngineInfo replayed_solver = exact;
  replayed_solver.contact_solver = {
      .kind = ContactSolverKind::box2d_2_4, .velocity_iterations = 8, .position_iterations = 3};
  CHECK(judge_bounce(run, scene, s, exact, h).follows);
  for (const EngineInfo& info : {exact, replayed_solver}) {
    const BounceVerdict v = judge_bounce(sparse, scene, s, info, h);
    CHECK(v.not_judged == "the run did not keep every step");
    CHECK_THAT(v.sentence(), Contains("not judged"));
  }
}
