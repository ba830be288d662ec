// Tests harness/judge/own_law.cpp: the own-law tolerance is finite wherever it passes anything.
// A law trajectory that reaches Inf or NaN has no tolerance (its scale is NaN), so no run follows
// it, however close; a finite law keeps a finite tolerance even where |x|^2 overflows; a NaN
// departure of the run counts as infinite, never as zero.
#include "harness/judge/own_law.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "harness/core/registry.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/scene/scene_loader.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;

namespace {

struct OwnLawCase {
  EngineInfo info;
  Trajectory law;  // free_fall's law at its step: finite, stable
};

OwnLawCase free_fall() {
  const Scene s = load_scene("scenarios/free_fall.toml");
  const EngineInfo info = make_engine("ours-f64")->info();
  return {info, predict_discrete(info.law, s, s.timestep.seconds)};
}

}  // namespace

TEST_CASE("a run identical to a finite law follows it within a finite tolerance", "[own_law]") {
  const OwnLawCase c = free_fall();
  const OwnLawVerdict v = judge_own_law(c.info, c.law, c.law, c.law);
  CHECK(v.tolerance.finite());
  CHECK(v.follows());
}

TEST_CASE("a law that reaches Inf or NaN gives no tolerance, and nothing follows it", "[own_law]") {
  for (double bad : {std::numeric_limits<double>::infinity(), std::nan("")}) {
    const OwnLawCase c = free_fall();
    Trajectory law = c.law;
    law.states[law.states.size() / 2].position.y() = bad;
    Trajectory run = law;  // the run equals the law wherever both are finite
    run.states[run.states.size() / 2].position.y() = 0.0;
    const OwnLawTolerance t = own_law_tolerance(c.info, law);
    INFO(bad << ": " << t.rule);
    CHECK_FALSE(t.finite());
    const OwnLawVerdict v = judge_own_law(c.info, run, law, law);
    CHECK_FALSE(v.follows());
    CHECK_THAT(v.sentence(), Contains("TOLERANCE NOT FINITE"));
    CHECK(v.sentence().find("nan") == std::string::npos);
    // Even a run with the very same non-finite value.
    CHECK_FALSE(judge_own_law(c.info, law, law, law).follows());
  }
}

TEST_CASE("a NaN in the run is an infinite departure from a finite law", "[own_law]") {
  const OwnLawCase c = free_fall();
  Trajectory run = c.law;
  run.states.back().velocity.x() = std::nan("");
  const OwnLawVerdict v = judge_own_law(c.info, run, c.law, c.law);
  CHECK(v.tolerance.finite());
  CHECK(std::isinf(v.residual_v));
  CHECK_FALSE(v.follows());
}

TEST_CASE("a finite law whose |x| overflows a squared norm still gets a finite tolerance",
          "[own_law]") {
  const OwnLawCase c = free_fall();
  Trajectory law = c.law;
  for (BodyState& b : law.states) b.position = Vec3(1e300, -1e300, 0.0);  // |x|^2 = Inf
  const OwnLawTolerance t = own_law_tolerance(c.info, law);
  CHECK(t.finite());
  CHECK(t.x == Approx(4.0 * 0x1p-52 * std::sqrt(2.0) * 1e300));
  CHECK(judge_own_law(c.info, law, law, law).follows());
}

TEST_CASE("an error-controlled engine's tolerance is its accuracy budget over its own steps",
          "[own_law][error-controlled]") {
  const Scene s = load_scene("scenarios/free_fall.toml");  // 1 s at 1/60 from rest: |v| <= 9.8
  EngineInfo info;
  info.law = kErrorControlled;
  info.accuracy = 1e-6;
  const Trajectory law = predict_discrete(info.law, s, 1.0 / 60.0);
  REQUIRE(law.engine == "law: " + to_string(kErrorControlled));
  // The law is the closed form: x = 10 - 4.9 t^2 at t = 1.
  CHECK(law.final_state(0).position.y() == Approx(5.1).epsilon(1e-15));
  // N*a*(sqrt(7) + sqrt(6)*max|v|*T) and N*a*sqrt(6)*max|v|, N the engine's steps (at least 60).
  const double vmax = 9.8;
  for (const std::int64_t steps : {0, 60, 90}) {
    const double n = steps < 60 ? 60.0 : static_cast<double>(steps);
    const OwnLawTolerance t = own_law_tolerance(info, law, steps);
    CHECK(t.x == Approx(n * 1e-6 * (std::sqrt(7.0) + std::sqrt(6.0) * vmax)).epsilon(1e-12));
    CHECK(t.v == Approx(n * 1e-6 * std::sqrt(6.0) * vmax).epsilon(1e-12));
    CHECK_THAT(t.rule, Contains("accuracy 1e-06 per step"));
  }
}

TEST_CASE("an error-controlled law without a closed form fails rather than passing on no samples",
          "[own_law][error-controlled]") {
  const Scene s = load_scene("scenarios/gazebo_boxes_simple.toml");  // turns: no closed form
  EngineInfo info;
  info.law = kErrorControlled;
  info.accuracy = 1e-3;
  const Trajectory law = predict_discrete(info.law, s, 1e-3);
  CHECK(law.status != RunStatus::ok);
  CHECK_THAT(law.failure, Contains("no closed form"));
  Trajectory run = law;  // a finished run: the failure is the law's
  run.status = RunStatus::ok;
  run.failure.clear();
  const OwnLawVerdict v = judge_own_law(info, run, law, law);
  CHECK_FALSE(v.follows());
  CHECK_THAT(v.failure, Contains("its law: no closed form"));
}
