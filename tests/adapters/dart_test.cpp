// Tests adapters/dart.cpp: DART 6.12 (Debian's double build) through the Engine interface, its own
// traps only: its declared law (implicit joint damping that equals phi after the forces), its drag
// figure, and the defaults it must not keep (gravity -9.81 along z, a 1 ms step). What every
// engine must do is in tests/adapters/conformance_test.cpp.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "adapter_test_support.hpp"
#include "harness/core/registry.hpp"
#include "harness/judge/bounce_verdict.hpp"
#include "harness/judge/landing_expectation.hpp"
#include "harness/judge/own_law.hpp"
#include "harness/judge/stack_verdict.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/oracles/identify_rotation.hpp"
#include "harness/oracles/landing.hpp"
#include "harness/run/runner.hpp"

using namespace dropcheck;
using dropcheck::testing::check_declared_law;
using dropcheck::testing::check_free_flight_law;
using dropcheck::testing::drag_figure_run;
using dropcheck::testing::scenario;

TEST_CASE("DART declares after-forces damping and follows it on every free-flight scene",
          "[dart][law]") {
  ENGINE_OR_RETURN(engine, "dart");
  check_declared_law("dart", Law{DampingOrder::AfterForces});
  CHECK(engine->info().scalar == Scalar::f64);
  // Every free-flight scene at its step, 1/30 and 1/240; measured 2.2e-15 to 4.0e-15 at 1/60.
  check_free_flight_law(*engine, [](std::int64_t) { return 1e-12; });
}

TEST_CASE("DART reproduces docs/engines.md's 60-step drag figure: ours's in double",
          "[dart][law]") {
  ENGINE_OR_RETURN(engine, "dart");
  // Gravity along -y at 9.8 and h = 1/60 reach DART only through the adapter (DART's own defaults
  // are (0, 0, -9.81) and 1 ms): the figure is ours-f64's position to the bit and MuJoCo's
  // velocity (3e-15 from ours-f64's), the implicit damping d = m*(exp(k*h) - 1)/h at work.
  const Trajectory run = drag_figure_run(*engine);
  CHECK(run.final_state(0).position.y() == Approx(6.5878983508563724).epsilon(0).margin(1e-12));
  CHECK(run.final_state(0).velocity.y() == Approx(-5.6219163479873915).epsilon(0).margin(1e-12));
  CHECK(run.final_state(0).position.z() == 0.0);
}

namespace {

// The box's sink below its start on each step of a run: y(0) - y(n).
std::vector<double> run_sink(const Trajectory& run) {
  std::vector<double> out;
  for (std::size_t k = 0; k < run.samples(); ++k)
    out.push_back(run.at(0, 0).position.y() - run.at(k, 0).position.y());
  return out;
}

}  // namespace

TEST_CASE("DART's box sinks into its floor as its relative CFM law says", "[dart][contact]") {
  // A resting or sliding box: d' = d - h*v', v' = (cfm*(v - g*h) + erp*d/h)/(1 + cfm), towards
  // cfm*g*h^2/erp. Measured in scratch runs of these scenes: 8e-14 m level, 2.9e-13 m on the
  // incline at 1/60.
  ENGINE_OR_RETURN(engine, "dart");
  const RelativeCfm law = engine->info().relative_cfm;
  REQUIRE(law.cfm == 1e-5);
  for (const char* name : {"slide_stop", "incline_slide"})
    for (double h : {1.0 / 60.0, 1.0 / 240.0}) {
      const Scene scene = scenario(name);
      const SlideSetup setup = slide_setups(scene).at(0);
      auto e = make_engine("dart");
      const Trajectory run = run_scene(*e, scene, h);
      REQUIRE(run.status == RunStatus::ok);
      const std::vector<double> sink = run_sink(run);
      NormalState s;
      double worst = 0.0;
      for (std::size_t k = 1; k < sink.size(); ++k) {
        normal_step(law, setup.g, h, s);
        worst = std::max(worst, std::abs(sink[k] - s.d));
      }
      INFO(name << " at h = " << h << ": worst " << worst << " m, last " << sink.back());
      CHECK(worst <= 1e-12);
      CHECK(sink.back() < steady_sink(law, setup.g, h));
    }
}

TEST_CASE("DART's slides follow the box pyramid's clamp law under its relative CFM",
          "[dart][contact]") {
  ENGINE_OR_RETURN(engine, "dart");
  CHECK(engine->info().friction_model == FrictionModel::box_pyramid);
  // Off its law (measured at 1/60): incline_slide, which never stops, 2.3e-11 m; the others up to
  // 1.1e-6 m along the slip, from the tilt the regularised rows give the box (about 1e-6 rad/s)
  // once it stops or while it slides at 45 degrees, which the law leaves out: every step stays
  // within 2e-6 m/s of the law from the run's own state.
  for (const char* name : {"slide_stop", "incline_slide", "incline_hold", "slide_diagonal"}) {
    const Scene scene = scenario(name);
    const SlideVerdict v = judged_slide("dart", scene, scene).verdict;
    INFO(name << ": " << v.sentence());
    CHECK(v.exact);
    CHECK(v.follows);
    if (std::string(name) == "incline_slide") CHECK(v.off_law <= 1e-10);
    // incline_hold's first cube is held: it creeps (1.5e-6 m by step 95) whatever its friction.
    if (std::string(name) == "incline_hold") continue;
    CHECK(v.seen.stop_step == v.law_seen.stop_step);
    // A friction coefficient 2 % off leaves the law.
    Scene off = scene;
    for (Body& b : off.bodies)
      if (b.friction) *b.friction *= 1.02;
    const SlideVerdict d = judged_slide("dart", off, scene).verdict;
    INFO("mu 2 % off: " << d.sentence());
    CHECK_FALSE(d.follows);
  }
}

TEST_CASE("DART turns as its FreeJoint keeps the turn, a rotation vector, and identify names it",
          "[dart][rotation]") {
  ENGINE_OR_RETURN(engine, "dart");
  const EngineInfo info = engine->info();
  CHECK(info.rotation_law ==
        RotationLaw{Gyroscopic::explicit_term, OrientationUpdate::exponential_map});
  CHECK(info.rotation_law.rotation_vector);
  CHECK(info.rotation_law.spatial_bias);
  // Gazebo's complex box (Dzhanibekov flips, |v| up to 90 m/s): measured 9.9e-11 rad at 1 ms and
  // 1.0e-8 rad at 1/60 from the round trip replayed in double, within the tolerance its spatial
  // bias adds (3.4e-7 rad at 1/60); the nearest other member, first-order, is 1.2e-4 rad away at 1
  // ms and 0.046 rad at 1/60.
  const Scene scene = scenario("gazebo_boxes_complex");
  for (const double h : {1e-3, 1.0 / 60.0}) {
    const Trajectory run = run_scene(*engine, scene, h);
    REQUIRE(run.status == RunStatus::ok);
    const OwnLawVerdict own = judge_own_law(info, scene, run);
    INFO("h = " << h << ": " << own.sentence());
    CHECK(own.follows());
    CHECK(own.residual_angle < 2e-8);
    EngineInfo wrong = info;
    wrong.rotation_law = {Gyroscopic::explicit_term, OrientationUpdate::first_order};
    CHECK_FALSE(judge_own_law(wrong, scene, run).follows());
    const RotationIdentification id = identify_rotation(scene, run);
    CHECK(id.fits[id.best].law == info.rotation_law);
  }
  // A turned box thrown without spin, of a mass that is no power of two: the law never turns it,
  // and the spatial bias's rounding v x m*v is all DART turns it by; held within the tolerance that
  // rounding adds.
  Scene turned = scenario("throw_3d");
  for (Body& b : turned.bodies)
    if (!b.is_static) {
      b.orientation = Quat(Eigen::AngleAxisd(0.5, Vec3(1.0, 2.0, 3.0).normalized()));
      b.angular_velocity = Vec3::Zero();
      b.mass = 3.0;
    }
  const Trajectory thrown = run_scene(*engine, turned, turned.timestep.seconds);
  REQUIRE(thrown.status == RunStatus::ok);
  const OwnLawVerdict still = judge_own_law(info, turned, thrown);
  INFO(still.sentence());
  CHECK(still.follows());
  // A spin about a principal axis with angular damping (implicit joint damping, after the forces):
  // the rotation vector's round trip replayed, 0 rad off.
  const Scene spin = scenario("spin_drag");
  const Trajectory run = run_scene(*engine, spin, spin.timestep.seconds);
  REQUIRE(run.status == RunStatus::ok);
  const OwnLawVerdict own = judge_own_law(info, spin, run);
  INFO(own.sentence());
  CHECK(own.follows());
  CHECK(own.residual_angle == 0.0);
}

TEST_CASE("DART runs every shipped contact scene, and no off-centre column", "[dart][contact]") {
  ENGINE_OR_RETURN(engine, "dart");
  for (const char* name : {"slide_stop", "incline_slide", "incline_hold", "slide_diagonal",
                           "drop_on_floor", "drop_on_floor_undamped", "bounce_e01", "bounce_e05",
                           "bounce_e09", "stack_rest", "tumble_drop"})
    CHECK(engine->cannot_run(scenario(name)).empty());
  Scene off = scenario("stack_rest");
  off.bodies[2].position.x() = 0.1;
  CHECK_THAT(engine->cannot_run(off), Catch::Contains("off-centre"));
}

TEST_CASE("DART's stack follows its centred column law exactly", "[dart][contact][stack]") {
  ENGINE_OR_RETURN(engine, "dart");
  // Measured at 1/60: 8.9e-16 m off the column at every step (medium 5.074e-6 m down after 5 s,
  // small 9.091e-6 m).
  const Scene scene = scenario("stack_rest");
  const StackSetup setup = stack_setups(scene).at(0);
  for (const Timestep& step : scene.timesteps) {
    const double h = step.seconds;
    const Trajectory run = run_scene(*engine, scene, h);
    REQUIRE(run.status == RunStatus::ok);
    for (const StackBodyVerdict& v : judge_stack(run, setup, engine->info(), h)) {
      INFO(step.text << ": " << v.sentence());
      CHECK(v.predicted.exact);
      CHECK(v.sink_ok);
      CHECK(v.drift_ok);
      CHECK(v.still_ok);
      CHECK(v.sink > 0.0);
    }
    // Without the corners' turning the law sinks a quarter as far: the check sees it.
    StackSetup rigid_turn = setup;
    for (StackLevel& l : rigid_turn.levels) l.corner_turn = 0.0;
    for (const StackBodyVerdict& v : judge_stack(run, rigid_turn, engine->info(), h))
      CHECK_FALSE(v.sink_ok);
  }
}

TEST_CASE("A DART landing climbs out of the floor at its capped push-out, step by step",
          "[dart][contact]") {
  ENGINE_OR_RETURN(engine, "dart");
  // Off the climb path at any step, measured over each scene's four steps: 3.6e-15 m
  // (drop_on_floor) and 6.5e-15 m (drop_on_floor_undamped) at 1/60, 2.3e-14 m at worst.
  for (const char* name : {"drop_on_floor", "drop_on_floor_undamped"}) {
    const Scene scene = scenario(name);
    const LandingSetup setup = landing_setups(scene).at(0);
    for (const Timestep& step : scene.timesteps) {
      const double h = step.seconds;
      const Trajectory run = run_scene(*engine, scene, h);
      REQUIRE(run.status == RunStatus::ok);
      const LandingExpectation expected = landing_expectation(engine->info(), scene, h, setup);
      REQUIRE(expected.climb.has_value());
      const double off = off_climb(run, setup, *expected.climb);
      INFO(name << " at " << step.text << ": " << off << " m off, climbing at "
                << expected.climb->climb << " m/s");
      CHECK(off <= 1e-12);
      if (step.text != "1/60") continue;
      // At 1/60 both land over 6 cm deep and climb at the cap less cfm times the step's fall.
      const double g = -scene.world.gravity.y();
      CHECK(expected.climb->climb == Approx(1e-3 - 1e-5 * g * h).epsilon(2e-4));
      CHECK(expected.rest_offset < -0.06);
      // A push-out cap twice DART's leaves the path by about 3 mm by the end.
      EngineInfo wrong = engine->info();
      wrong.relative_cfm.max_push = 2e-3;
      CHECK(off_climb(run, setup, *landing_expectation(wrong, scene, h, setup).climb) > 2e-3);
    }
  }
}

TEST_CASE("DART's bounce follows its law: the rebound of the post-gravity approach, regularised",
          "[dart][contact]") {
  ENGINE_OR_RETURN(engine, "dart");
  // The impact step starts 4.41 m/s down; its LCP sees the approach after that step's gravity,
  // 4.41 + g*h, asks for e times it and, regularised, stops 1/(1 + cfm) of the way there from the
  // free velocity: (e - cfm)*(4.41 + g*h)/(1 + cfm). The apexes are those of that law stepped by
  // hand (a separate script, not bounce_path). Measured off the law at 1/60: 3.3e-16, 6.0e-16 and
  // 2.7e-15 m. At e = 0.1 the sphere leaves from 7 cm deep at 0.457 m/s and never clears the floor:
  // it climbs out at the push-out's cap, so there is no apex.
  const double approach = 4.41 + 9.8 / 60.0;
  const auto out = [&](double e) { return (e - 1e-5) * approach / (1.0 + 1e-5); };
  check_bounces(*engine, {{"bounce_e01", 1e-15, out(0.1), -2.0},
                          {"bounce_e05", 1e-15, out(0.5), 0.2568173268267318},
                          {"bounce_e09", 3e-15, out(0.9), 0.8698401243765337}});
  // Each member matters: the step-start approach, or no regularisation, or e 2 % off, leaves it.
  const Scene scene = scenario("bounce_e05");
  const double h = scene.timestep.seconds;
  const Trajectory run = run_scene(*engine, scene, h);
  const BounceSetup setup = bounce_setups(scene).at(0);
  BounceLaw start = engine->info().bounce_law, rigid = start;
  start.free_approach = false;
  rigid.cfm = 0.0;
  CHECK_FALSE(judge_bounce(run, setup, start, h).follows);
  CHECK_FALSE(judge_bounce(run, setup, rigid, h).follows);
  BounceSetup off = setup;
  off.e *= 1.02;
  CHECK_FALSE(judge_bounce(run, off, engine->info().bounce_law, h).follows);
}
