// Tests adapters/dart.cpp: DART 6.12 (Debian's double build) through the Engine interface, its own
// traps only: its declared law (implicit joint damping that equals phi after the forces), its drag
// figure, and the defaults it must not keep (gravity -9.81 along z, a 1 ms step). What every
// engine must do is in tests/adapters/conformance_test.cpp.
#include <catch2/catch.hpp>

#include "adapter_test_support.hpp"
#include "harness/core/registry.hpp"
#include "harness/oracles/discrete_law.hpp"
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
