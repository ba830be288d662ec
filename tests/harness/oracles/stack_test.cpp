// Tests harness/oracles/stack.cpp and harness/core/stack_law.cpp: the columns a scene holds, and
// what each engine's stack law predicts, against the closed forms docs/contact.md derives (each
// recomputed here from its parameters).
#include "harness/oracles/stack.hpp"

#include <catch2/catch.hpp>
#include <cmath>

#include "harness/scene/scene_loader.hpp"
#include "tests/shipped_scenes.hpp"

using namespace dropcheck;

namespace {

constexpr double kGravity = 9.8, kH = 1.0 / 60.0;
const StackLaw kOdeStack{.compliance = 1e-10 / 0.2, .points = 4};
const StackLaw kMujoco{.soft = 1e-4 * 1.25 / 16.0, .tau_steps = 2.0};

}  // namespace

TEST_CASE("a stack is a column of resting boxes over a floor, bottom up", "[contact][stack]") {
  const std::vector<StackSetup> seed = stack_setups(testing::shipped("stack_rest"));
  REQUIRE(seed.size() == 1);
  REQUIRE(seed[0].levels.size() == 2);
  // The medium cube (1.5 m) on the floor, the small one (1 m) on it: centres at 0.75 and 2 m.
  CHECK(seed[0].levels[0].rest_height == 0.75);
  CHECK(seed[0].levels[1].rest_height == 2.0);
  CHECK(seed[0].levels[0].load == 2.0);  // kg: itself and the small cube
  CHECK(seed[0].levels[1].mass_below == 1.0);
  // mass_ratio: each heavy cube is dropped from 1 m above its light one: two columns.
  const std::vector<StackSetup> ratio = stack_setups(testing::shipped("extreme/mass_ratio"));
  REQUIRE(ratio.size() == 2);
  CHECK(ratio[1].levels[0].load == 100001.0);
  CHECK(ratio[1].levels[1].rest_height == 1.5);
  // A third cube beside the small one, overlapping the medium's footprint: its load would go
  // uncounted, so the column is not a stack the law can judge.
  Scene crowded = testing::shipped("stack_rest");
  Body extra = crowded.bodies[2];
  extra.name = "extra";
  extra.position = {1.0, 2.0, 0.0};  // over the medium cube's edge (half extent 0.75)
  crowded.bodies.push_back(extra);
  CHECK(stack_setups(crowded).empty());
  // A centre exactly on the edge of the face below balances: not carried by that column alone.
  Scene edge = testing::shipped("stack_rest");
  edge.bodies[2].position.x() = 0.75;
  CHECK(stack_setups(edge).empty());
  // One body alone is a landing; a slide is not at rest.
  CHECK(stack_setups(testing::shipped("drop_on_floor")).empty());
  CHECK(stack_setups(testing::shipped("slide_stop")).empty());
}

TEST_CASE("stack laws: ODE's constraint force mixing and MuJoCo's soft sag", "[contact][stack]") {
  // ODE: CFM/h*f = ERP/h^2*depth per point, depth = CFM/ERP*h*W/4: 1 kg on the floor at 1/60 is
  // 5e-10/60*9.8/4 = 2.0417e-11 m, the rest offset its landings measure (-2.04e-11 m).
  CHECK(contact_sink(kOdeStack, kGravity, 1.0, 0.0, kH) ==
        Approx(5e-10 / 60.0 * 9.8 / 4.0).epsilon(1e-15));
  CHECK(contact_sink(kOdeStack, kGravity, 1.0, 0.0, kH) == Approx(2.0417e-11).epsilon(1e-4));
  // MuJoCo: (1 - d)*(1 + mu^2)/16*(2h)^2*W*(1/m_a + 1/m_b): 1 kg under 1e5 kg at 1/240 is
  // 1e-4*1.25/16*(1/120)^2*100001*9.8 = 5.3169e-4 m.
  CHECK(contact_sink(kMujoco, 100001.0 * kGravity, 1.0, 0.0, 1.0 / 240.0) ==
        Approx(1e-4 * 1.25 / 16.0 / 14400.0 * 100001.0 * kGravity).epsilon(1e-15));
  // The upper contact of a stack acts on both bodies: the small cube on the medium one sinks as
  // the medium one on the floor carrying twice the weight.
  CHECK(contact_sink(kMujoco, kGravity, 1.0, 1.0, kH) ==
        Approx(contact_sink(kMujoco, 2 * kGravity, 1.0, 0.0, kH)));
  // Predicted per level: the sinks of every contact under it, summed.
  const StackSetup s = stack_setups(testing::shipped("extreme/mass_ratio"))[1];
  EngineInfo ode;
  ode.stack_law = kOdeStack;
  const double bottom = contact_sink(kOdeStack, 100001.0 * kGravity, 1.0, 0.0, kH);
  CHECK(predict_stack(s, 0, ode, kH, 300).sink == bottom);
  CHECK(predict_stack(s, 1, ode, kH, 300).sink ==
        Approx(bottom + contact_sink(kOdeStack, 1e5 * kGravity, 1e5, 1.0, kH)).epsilon(1e-15));
  CHECK(predict_stack(s, 1, ode, kH, 300).residual == 0.0);  // a direct solver converges
}

TEST_CASE("an iterative solver's sweeps: the residual L/(L + m) per sweep", "[contact][stack]") {
  // Two contacts, floor-light (1/m) and light-heavy (1/m + 1/M): the Gauss-Seidel iteration matrix
  // of their 2x2 system has spectral radius (1/m^2)/((1/m)*(1/m + 1/M)) = M/(M + m).
  const StackLaw bullet{.iterations = 10};
  CHECK(sweep_residual(bullet, 1000.0, 1.0) == Approx(std::pow(1000.0 / 1001.0, 10)));
  CHECK(sweep_residual(bullet, 1000.0, 1.0) > kUnheldResidual);          // 0.990: cannot hold
  CHECK(sweep_residual(bullet, 1.0, 1.0) == Approx(std::pow(0.5, 10)));  // the seed's: holds
  CHECK(sweep_residual(StackLaw{}, 1000.0, 1.0) == 0.0);
  const StackSetup s = stack_setups(testing::shipped("extreme/mass_ratio"))[0];
  EngineInfo box2d;
  box2d.stack_law = {.iterations = 8};
  const StackPrediction p = predict_stack(s, 1, box2d, kH, 300);
  CHECK(p.residual == Approx(std::pow(1000.0 / 1001.0, 8)));
  CHECK(p.load == 1000.0);
  CHECK(p.mass == 1.0);
}

TEST_CASE("a relative CFM column: one box as the floor contact's law, two as their closed forms",
          "[contact][stack]") {
  const RelativeCfm dart{.cfm = 1e-5, .erp = 0.01, .max_push = 1e-3};
  Scene scene = testing::shipped("stack_rest");
  scene.world.damping_rate = 0.0;
  StackSetup s = stack_setups(scene).at(0);
  // Corner turning of a cube of side 2a and mass m at its corner (+-a, +-a): 2a^2/(m*(2a)^2/6) =
  // 3/m; the small cube's corners on the medium one's top, 0.5 m off its axis: 2*0.25/(1.5^2/6).
  CHECK(s.levels[0].corner_turn == Approx(3.0).epsilon(1e-15));
  CHECK(s.levels[1].corner_turn == Approx(3.0 + 0.5 / (2.25 / 6.0)).epsilon(1e-15));
  CHECK(s.levels[1].centred);
  // One box alone: its corner row's diagonal entry is 4/m, so the row stops 1/(1 + cfm) of the way
  // from v_free to the push-out: the floor contact's law (harness/core/relative_cfm.hpp) step by
  // step.
  StackSetup one = s;
  one.levels.resize(1);
  one.levels[0].load = one.levels[0].mass;
  for (const std::int64_t steps : {1, 2, 10, 300}) {
    NormalState m;
    for (std::int64_t k = 0; k < steps; ++k) normal_step(dart, kGravity, kH, m);
    CHECK(relative_cfm_column(one, dart, kH, steps).sink.at(0) == Approx(m.d).epsilon(1e-9));
  }
  // Two: at rest each corner carries W_k*h/4 and its push-out erp*d_k/h meets cfm*A_k*W_k*h/4, so
  // d_k = cfm/erp*h^2*W_k*A_k/4, reached by about (1 - erp) a step.
  const ColumnPath settled_path = relative_cfm_column(s, dart, kH, 6000, 5000);
  const std::vector<double>& settled = settled_path.sink;
  CHECK(settled_path.past_faces == -1);
  CHECK(settled_path.still[1].speed < 1e-15);
  const double a0 = 1.0 + 3.0, a1 = 2.0 + s.levels[1].corner_turn;
  const double d0 = 1e-3 * kH * kH * 2.0 * kGravity * a0 / 4.0;
  const double d1 = 1e-3 * kH * kH * 1.0 * kGravity * a1 / 4.0;
  CHECK(settled[0] == Approx(d0).epsilon(1e-9));
  CHECK(settled[1] == Approx(d0 + d1).epsilon(1e-9));
  // An off-centre column is outside the law.
  s.levels[1].centred = false;
  CHECK_THROWS_AS(relative_cfm_column(s, dart, kH, 1), std::invalid_argument);
}

TEST_CASE("a relative CFM column whose capped push-out cannot carry its load sinks past its faces",
          "[contact][stack]") {
  // A 1 kg cube under 1e5 kg: at rest its corners would need a push-out of cfm*A*W*h/4 = 0.16 m/s
  // against DART's cap of 1e-3 m/s, so the column sinks on, and the heavy cube's centre passes the
  // light one's top within the 5 s run; under 1e3 kg each contact sinks at about 0.6 mm/s, within
  // its faces.
  const RelativeCfm dart{.cfm = 1e-5, .erp = 0.01, .max_push = 1e-3};
  const std::vector<StackSetup> columns = stack_setups(testing::shipped("extreme/mass_ratio"));
  REQUIRE(columns.size() == 2);
  const ColumnPath light = relative_cfm_column(columns[0], dart, kH, 300, 180);
  const ColumnPath heavy = relative_cfm_column(columns[1], dart, kH, 300, 180);
  CHECK(light.past_faces == -1);
  CHECK(light.still[0].speed == Approx(6e-4).epsilon(0.2));  // the run: 6e-4 and 1.2e-3 m/s
  CHECK(light.still[1].speed == Approx(1.2e-3).epsilon(0.2));
  CHECK(heavy.past_faces > 100);
  CHECK(heavy.past_faces <= 202);  // DART leaves the law at step 202 (measured)
}
