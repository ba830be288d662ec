// Tests harness/measure/own_law.cpp: the own-law tolerance is finite wherever it passes anything.
// A law trajectory that reaches Inf or NaN has no tolerance (its scale is NaN), so no run follows
// it, however close; a finite law keeps a finite tolerance even where |x|^2 overflows; a NaN
// departure of the run counts as infinite, never as zero.
#include "harness/measure/own_law.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "harness/core/registry.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/scene/scene_loader.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;

namespace {

struct Case {
  EngineInfo info;
  Trajectory law;  // free_fall's law at its step: finite, stable
};

Case free_fall() {
  const Scene s = load_scene("scenarios/free_fall.toml");
  const EngineInfo info = make_engine("ours-f64")->info();
  return {info, predict_discrete(info.law, s, s.timestep.seconds)};
}

}  // namespace

TEST_CASE("a run identical to a finite law follows it within a finite tolerance", "[own_law]") {
  const Case c = free_fall();
  const OwnLawVerdict v = judge_own_law(c.info, c.law, c.law, c.law);
  CHECK(v.tolerance.finite());
  CHECK(v.follows());
}

TEST_CASE("a law that reaches Inf or NaN gives no tolerance, and nothing follows it", "[own_law]") {
  for (double bad : {std::numeric_limits<double>::infinity(), std::nan("")}) {
    const Case c = free_fall();
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
  const Case c = free_fall();
  Trajectory run = c.law;
  run.states.back().velocity.x() = std::nan("");
  const OwnLawVerdict v = judge_own_law(c.info, run, c.law, c.law);
  CHECK(v.tolerance.finite());
  CHECK(std::isinf(v.residual_v));
  CHECK_FALSE(v.follows());
}

TEST_CASE("a finite law whose |x| overflows a squared norm still gets a finite tolerance",
          "[own_law]") {
  const Case c = free_fall();
  Trajectory law = c.law;
  for (BodyState& b : law.states) b.position = Vec3(1e300, -1e300, 0.0);  // |x|^2 = Inf
  const OwnLawTolerance t = own_law_tolerance(c.info, law);
  CHECK(t.finite());
  CHECK(t.x == Approx(4.0 * 0x1p-52 * std::sqrt(2.0) * 1e300));
  CHECK(judge_own_law(c.info, law, law, law).follows());
}
