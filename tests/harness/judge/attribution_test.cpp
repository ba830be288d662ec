// Tests harness/judge/attribution.cpp: a divergence built from the exact discrete laws is all
// "law part"; a perturbed engine leaves a residual that is flagged; lengths print in readable
// units.
#include "harness/judge/attribution.hpp"

#include <catch2/catch.hpp>

#include "harness/oracles/discrete_law.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;

namespace {

// The seed's drop: 10 m, g = -9.8, drag 0.98 per step at 60 Hz (k = -ln(0.98)*60), 1 s.
Scene drop() {
  Scene s;
  s.name = "drop";
  s.duration = 1.0;
  s.world = {.gravity = {0.0, -9.8, 0.0}, .damping_rate = -std::log(0.98) * 60.0};
  s.bodies = {{.name = "cube", .position = {0.0, 10.0, 0.0}}};
  return s;
}

// A double engine whose operation order the harness does not copy (like Bullet or ODE).
EngineInfo info(const char* name, Law law) {
  EngineInfo i;
  i.name = name;
  i.scalar = Scalar::f64;
  i.law = law;
  return i;
}

}  // namespace

TEST_CASE("the attribution of Bullet's law against ours' law is all of it from the laws",
          "[attribution]") {
  const Scene s = drop();
  const double h = 1.0 / 60;
  const Trajectory bullet = predict_discrete(DampingOrder::BeforeForces, s, h);
  const Trajectory ours = predict_discrete(DampingOrder::AfterForces, s, h);
  const EngineInfo bi = info("bullet", DampingOrder::BeforeForces),
                   oi = info("ours-f64", DampingOrder::AfterForces);
  const Attribution a = attribute({bi, bullet, bullet, bullet}, {oi, ours, ours, ours}, true);
  // docs/engines.md 2: 6.5878983508563724 - 6.5182636233228308 m after 60 steps.
  CHECK(a.final_total == Approx(6.5878983508563724 - 6.5182636233228308).epsilon(1e-12));
  CHECK(a.total == a.final_total);  // the gap grows monotonically
  CHECK(a.law_part == a.total);
  CHECK(a.residual == 0.0);
  CHECK(a.budget > 0.0);
  CHECK(a.budget < 1e-11);  // 16 ulps per step of 10 m over 60 steps, twice: 4.3e-12 m
  CHECK(a.explained());
  CHECK_THAT(a.sentence(),
             Contains("6.96 cm at t = 1 s") && Contains("all of it from the two discrete laws"));
}

TEST_CASE(
    "the attribution blames the engine that departs from its own law, never the one that follows "
    "it",
    "[attribution]") {
  const Scene s = drop();
  const double h = 1.0 / 60;
  const Trajectory law = predict_discrete(DampingOrder::BeforeForces, s, h);
  const Trajectory ours = predict_discrete(DampingOrder::AfterForces, s, h);
  Trajectory engine = law;  // as if gravity were -10 instead of -9.8: 0.1*t^2 m off by t = 1 s
  for (std::size_t i = 0; i < engine.samples(); ++i)
    engine.states[i].position.y() -= 0.1 * engine.time(i) * engine.time(i);
  const EngineInfo bi = info("bullet", DampingOrder::BeforeForces),
                   oi = info("ours-f64", DampingOrder::AfterForces);
  const Attribution a = attribute({bi, engine, law, law}, {oi, ours, ours, ours}, true);
  CHECK_FALSE(a.explained());
  CHECK(a.blamed() == "bullet");
  CHECK(a.residual == Approx(0.1).epsilon(1e-9));
  CHECK_THAT(a.sentence(), Contains("UNEXPLAINED residual 10 cm") &&
                               Contains("bullet departs from its own law") &&
                               Contains("ours-f64 follows its own law to 0 m"));
  // The same departure in the reference is blamed on the reference, not on bullet.
  const Attribution r = attribute({bi, law, law, law}, {oi, engine, ours, ours}, true);
  CHECK(r.blamed() == "ours-f64");
  CHECK_THAT(r.sentence(), Contains("bullet follows its own law to 0 m") &&
                               Contains("ours-f64 departs from its own law"));
}

TEST_CASE("the attribution of two engines on the same law is rounding only", "[attribution]") {
  const Scene s = drop();
  const Trajectory law = predict_discrete(DampingOrder::AfterForces, s, 1.0 / 60);
  Trajectory f32 = law;
  for (BodyState& st : f32.states) st.position.y() = static_cast<float>(st.position.y());
  // An f32 engine following its law in its own arithmetic (here: the law rounded to float).
  EngineInfo fi = info("ours", DampingOrder::AfterForces);
  fi.scalar = Scalar::f32;
  const EngineInfo oi = info("ours-f64", DampingOrder::AfterForces);
  const Attribution a = attribute({fi, f32, f32, law}, {oi, law, law, law}, true);
  CHECK(a.law_part == 0.0);
  CHECK(a.residual == 0.0);
  CHECK(a.precision_part > 0.0);  // what float costs, measured rather than budgeted
  CHECK(a.explained());
  CHECK_THAT(a.sentence(), Contains("the two discrete laws agree, so all of it is rounding"));
  CHECK_THAT(attribute({oi, law, law, law}, {oi, law, law, law}, true).sentence(),
             Contains("identical"));
}

TEST_CASE("an error-controlled engine adds its measured departure to the budget, not its accuracy",
          "[attribution][error-controlled]") {
  const Scene s = drop();
  const double h = 1.0 / 60;
  // The continuous model (the error-controlled member's law), and a run 1 um off it.
  const Trajectory model = predict_discrete(kErrorControlled, s, h);
  Trajectory run = model;
  for (BodyState& b : run.states) b.position.y() += 1e-6;
  const Trajectory ours = predict_discrete(DampingOrder::AfterForces, s, h);
  EngineInfo ri = info("simbody-rkm", kErrorControlled);
  ri.accuracy = 1e-3;  // a budget near 1 m: as a rounding bound it would swallow every law part
  const Attribution a =
      attribute({ri, run, model, model},
                {info("ours-f64", DampingOrder::AfterForces), ours, ours, ours}, true);
  CHECK(a.engine_law.follows());
  CHECK(a.engine_law.tolerance.x > 0.5);
  CHECK(a.budget == Approx(1e-6).epsilon(1e-5));  // 1 um, plus ours-f64's 2e-12 m rounding bound
  CHECK(a.law_part > 0.01);                       // semi-implicit Euler against the model: cm
  CHECK(a.law_difference == "scheme");
  CHECK_THAT(a.sentence(), Contains("from the two discrete laws (scheme)"));
}
