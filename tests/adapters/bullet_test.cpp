// Tests adapters/bullet.cpp: Bullet 3.24 (Debian's float64 build by default) through the Engine
// interface, its own traps only: its declared law and drag figure (docs/engines.md section 2) and
// the damping rates its per-second parameter cannot hold. What every engine must do (its own law, a
// force for one step, reload, static bodies, landing) is in tests/adapters/conformance_test.cpp.
// Set DROPCHECK_MEASURE=1 to print the measured figures.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

#include "adapter_test_support.hpp"
#include "harness/core/registry.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/run/runner.hpp"

using namespace dropcheck;
using dropcheck::testing::check_bounces;
using dropcheck::testing::drag_figure_run;
using dropcheck::testing::scenario;

namespace {

bool measuring() {
  return std::getenv("DROPCHECK_MEASURE") != nullptr;
}

// Rounding of a run against its own law (m, m/s). Double: measured worst 1.8e-13 m and 1.1e-13 m/s
// (seed_part3 at 1/240); at 1/60 2.1e-14 m, at 1/30 1.4e-14 m. Float build
// (DROPCHECK_BULLET_PRECISION=float): measured worst 1.8e-5 m (seed_part3 at 1/60) and 1.5e-5 m/s
// (free_fall at 1/240).
double law_tolerance(Scalar s) {
  return s == Scalar::f64 ? 1e-9 : 1e-4;
}

// The largest |engine - law| component of any body at any sample, and where it happened.
struct Worst {
  double dx = 0.0, dv = 0.0;
  std::string where = "nowhere";
};

std::string describe(const Trajectory& run, const Trajectory& law, std::size_t s, std::size_t b) {
  std::ostringstream m;
  m.precision(17);
  const BodyState &e = run.at(s, b), &l = law.at(s, b);
  m << "scene " << run.scene << ", engine " << run.engine << ", body " << run.body_names[b]
    << ", step " << run.recorded[s] << " (h = " << run.h << "): engine x = ("
    << e.position.transpose() << ") v = (" << e.velocity.transpose() << "), law x = ("
    << l.position.transpose() << ") v = (" << l.velocity.transpose() << ")";
  return m.str();
}

Worst worst_vs_law(const Trajectory& run, const Trajectory& law) {
  Worst w;
  for (std::size_t s = 0; s < run.samples(); ++s) {
    for (std::size_t b = 0; b < run.bodies(); ++b) {
      const double dx = (run.at(s, b).position - law.at(s, b).position).cwiseAbs().maxCoeff();
      const double dv = (run.at(s, b).velocity - law.at(s, b).velocity).cwiseAbs().maxCoeff();
      if (std::max(dx, dv) > std::max(w.dx, w.dv)) w.where = describe(run, law, s, b);
      w.dx = std::max(w.dx, dx);
      w.dv = std::max(w.dv, dv);
    }
  }
  return w;
}

}  // namespace

// Its own law at every step of every shipped scene, and the declaration it is checked against, are
// in tests/adapters/conformance_test.cpp.
TEST_CASE("Bullet reproduces docs/engines.md's 60-step drag figure", "[bullet][law]") {
  ENGINE_OR_RETURN(engine, "bullet");
  const Trajectory run = drag_figure_run(*engine);
  const double x = run.final_state(0).position.y();
  if (engine->info().scalar == Scalar::f64) {
    // Measured 6.5182636233228308 exactly (docs/engines.md section 2); 1e-12 leaves room for libm.
    CHECK(x == Approx(6.5182636233228308).epsilon(0).margin(1e-12));
  } else {
    CHECK(x == Approx(6.5182623863220215)
                   .epsilon(0)
                   .margin(1e-6));  // float libs, docs/engines.md section 2
  }
}

TEST_CASE("Bullet refuses a damping rate its per-second parameter cannot hold", "[bullet][law]") {
  ENGINE_OR_RETURN(engine, "bullet");
  // k = 60 1/s (scenarios/extreme/heavy_drag): d = 1 - exp(-60) = 1 - 8.8e-27 rounds to 1, and
  // Bullet's (1 - d)^h would be 0 instead of exp(-k*h) = 0.61 at 1/120.
  Scene scene = scenario("free_fall");
  scene.world.damping_rate = 60.0;
  CHECK_THAT(engine->cannot_run(scene),
             Catch::Contains("engine limit") && Catch::Contains("to 0.0 digits"));
  const Trajectory run = run_scene(*engine, scene, 1.0 / 120.0);
  CHECK(run.status == RunStatus::engine_error);
  CHECK_THAT(run.failure, Catch::Contains("damping rate k = 60"));
  // Below the limit Bullet runs, but 1 - d carries a relative rounding of up to spacing/exp(-k),
  // and phi = (1 - d)^h h times that: k = 15 1/s holds in double (measured |dx| 3.4e-12 m at
  // 1/120); float needs k = 5 1/s (1 - d = 6.7e-3, rounding 4.5e-6; measured |dx| 4.2e-6 m).
  const bool f64 = engine->info().scalar == Scalar::f64;
  // k = 30 1/s keeps 2.9 digits in double (it drifted 9.2 um from exp(-k*h)): refused, with the
  // reason.
  scene.world.damping_rate = 30.0;
  if (f64)
    CHECK_THAT(engine->cannot_run(scene),
               Catch::Contains("to 2.9 digits") && Catch::Contains("k <= 22.9 1/s"));
  scene.world.damping_rate = f64 ? 15.0 : 5.0;
  CHECK(engine->cannot_run(scene).empty());
  const Trajectory ok = run_scene(*engine, scene, 1.0 / 120.0);
  REQUIRE(ok.status == RunStatus::ok);
  const Worst w = worst_vs_law(ok, predict_discrete(engine->info().law, scene, 1.0 / 120.0));
  INFO(w.where);
  if (measuring())
    WARN("k = " << scene.world.damping_rate << ": |dx| " << w.dx << " |dv| " << w.dv);
  CHECK(w.dx <= law_tolerance(engine->info().scalar));
}

TEST_CASE(
    "Bullet's bounce follows its law: restitution above 0.2 m/s, split-impulse push-out, "
    "speculative contact within 0.02 of the sphere's bounding radius",
    "[bullet][contact]") {
  ENGINE_OR_RETURN(engine, "bullet");
  // Measured: 2.2e-16, 2.0e-15 and 1.7e-14 m from its law over each run. The speculative contact
  // (0.02*sqrt(3)*0.5 = 0.01732 m for the 0.5 m sphere) and the push-out in position take it off
  // the ideal law: the push moves the first apex up by 0.2*0.029 m (0.2435778 against 0.2377778 at
  // e = 0.5), and at e = 0.9 the second apex is 0.3501 m against the ideal law's 0.6469.
  check_bounces(*engine, {{"bounce_e01", 2.2e-16, 0.441, -2.0},
                          {"bounce_e05", 2.0e-15, 2.205, 0.2435778},
                          {"bounce_e09", 1.7e-14, 3.969, 0.8138833}});
  const Scene high = scenario("bounce_e09");
  const BounceSetup s = bounce_setups(high).at(0);
  CHECK(s.size == Approx(0.5 * std::sqrt(3.0)).epsilon(1e-15));
  const BounceVerdict v = judge_bounce(run_scene(*engine, high, high.timestep.seconds), s,
                                       engine->info().bounce_law, high.timestep.seconds);
  REQUIRE(v.seen.apexes.size() == 3);
  CHECK(v.seen.apexes[1] == Approx(0.3501).epsilon(1e-3));
  CHECK(v.ideal.apexes[1] == Approx(0.6469).epsilon(1e-3));
  REQUIRE(v.causes.size() == 2);
  CHECK_THAT(v.causes[1], Catch::Contains("speculative contact") && Catch::Contains("0.01732 m"));
}

TEST_CASE("Bullet's slides keep Coulomb's law with their own normal impulses, and 2 % off does not",
          "[bullet][contact]") {
  ENGINE_OR_RETURN(engine, "bullet");
  CHECK(engine->info().friction_model == FrictionModel::cone);
  CHECK(engine->info().contact_solver.kind == ContactSolverKind::bullet_3);
  // Measured (double, 1/60): the median slipping step's friction is mu*N to 7.9e-6 (slide_stop)
  // and 1.5e-8 (incline_slide); whole slides 0.999 to 1.005 of it, single steps off by up to 15 %
  // as the box rocks on its manifold's corners.
  for (const char* name : {"slide_stop", "incline_slide", "incline_hold", "slide_diagonal"}) {
    const Scene scene = scenario(name);
    const std::size_t slides = slide_setups(scene).size();
    for (std::size_t k = 0; k < slides; ++k) {
      const SlideVerdict v = judged_slide("bullet", scene, scene, false, k).verdict;
      INFO(name << ", slide " << k << ": " << v.sentence());
      CHECK(v.exact);
      REQUIRE(v.coulomb.has_value());
      CHECK(v.follows);
      CHECK(v.coulomb->pull_step < 0);
      if (v.coulomb->slipping > 0) CHECK(std::abs(v.coulomb->median_ratio - 1.0) < 1e-4);
    }
    // The scene's mu mapped 2 % off, either way: every slipping step moves, the median with them.
    for (double factor : {1.02, 0.98}) {
      Scene off = scene;
      for (Body& b : off.bodies)
        if (b.friction) *b.friction *= factor;
      const SlideVerdict d = judged_slide("bullet", off, scene, false, slides - 1).verdict;
      INFO(name << ", mu x " << factor << ": " << d.sentence());
      CHECK_FALSE(d.follows);
      CHECK_THAT(d.sentence(), Catch::Contains("another coefficient or combine rule"));
    }
  }
}
