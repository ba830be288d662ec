// Tests harness/core/relative_cfm.cpp: the floor contact's normal side under relative constraint
// force mixing, against its closed forms.
#include "harness/core/relative_cfm.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace dropcheck;

TEST_CASE("a rigid contact cancels the approach and sinks nothing", "[contact][cfm]") {
  NormalState s;
  const double g = 9.8, h = 1.0 / 60.0;
  for (int n = 0; n < 10; ++n) CHECK(normal_step(RelativeCfm{}, g, h, s) == g * h);
  CHECK(s.v == 0.0);
  CHECK(s.d == 0.0);
  CHECK(steady_sink(RelativeCfm{}, g, h) == 0.0);
  CHECK(describe(RelativeCfm{}) == "none");
}

TEST_CASE("under relative CFM a resting box sinks towards cfm*g*h^2/erp", "[contact][cfm]") {
  const RelativeCfm dart{.cfm = 1e-5, .erp = 0.01};
  const double g = 9.8, h = 1.0 / 60.0;
  NormalState s;
  // Step 1 from rest at the surface: v = -cfm*g*h/(1 + cfm), so d = cfm*g*h^2/(1 + cfm).
  const double impulse = normal_step(dart, g, h, s);
  CHECK(s.d == Approx(1e-5 * g * h * h / (1.0 + 1e-5)).epsilon(1e-14));
  CHECK(impulse == Approx(g * h / (1.0 + 1e-5)).epsilon(1e-14));
  // Then d' = (1 - erp/(1 + cfm))*d + cfm*g*h^2/(1 + cfm) (with v carried): a fixed point at
  // cfm*g*h^2/erp = 2.7222e-6 m, approached by about 0.99 a step.
  const double steady = steady_sink(dart, g, h);
  CHECK(steady == Approx(1e-5 * 9.8 / 3600.0 / 0.01).epsilon(1e-15));
  for (int n = 1; n < 4000; ++n) normal_step(dart, g, h, s);
  CHECK(std::abs(s.d - steady) <= 1e-12 * steady);
  CHECK(std::abs(s.v) <= 1e-15 * g * h);  // at rest, to rounding of the step's g*h
  CHECK(describe(dart) ==
        "constraint force mixing 1e-05 of each diagonal entry, error reduction 0.01");
}
