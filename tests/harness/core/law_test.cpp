// The law family (harness/core/law.hpp): each member against its closed form for a constant
// acceleration, and the keys that name members on the command line and in files.
#include "harness/core/law.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

namespace dropcheck {
namespace {

// Without damping (phi = 1) and a constant a, after n steps from (x0, v0):
//   semi-implicit: v_n = v0 + n*a*h,  x_n = x0 + n*h*v0 + a*h^2 * n*(n+1)/2
//   explicit:      v_n = v0 + n*a*h,  x_n = x0 + n*h*v0 + a*h^2 * n*(n-1)/2
TEST_CASE("law family: every undamped member matches its closed form", "[law][reference]") {
  const long double h = 0.01L, a = -9.8L, x0 = 10.0L, v0 = 3.0L;
  const int n = 500;
  for (Law law : kLawFamily) {
    if (law.scheme != Scheme::Euler) continue;  // RK4: its own tests below
    long double x = x0, v = v0;
    for (int i = 0; i < n; ++i) advance(law, 1.0L, h, a, x, v);
    const long double m = law.position == PositionUpdate::Explicit ? n - 1 : n + 1;
    const long double x_closed = x0 + n * h * v0 + a * h * h * n * m / 2;
    INFO(law_key(law));
    CHECK(std::abs(static_cast<double>(x - x_closed)) < 1e-12);  // measured 0 to 2e-15
    CHECK(std::abs(static_cast<double>(v - (v0 + n * a * h))) < 1e-12);
  }
}

// With damping and a = 0 every member decays v by phi per step; the position sums h*v over the
// velocities the member moves with: the damped new ones (phi + ... + phi^n) for semi-implicit
// BeforeForces and AfterForces, the old ones (1 + ... + phi^(n-1)) for explicit members and for
// AfterPosition (it moves with v + a*h and damps afterwards).
TEST_CASE("law family: damping decays the velocity by phi per step in every member", "[law]") {
  const double phi = 0.98, h = 1.0 / 60.0;
  for (Law law : kLawFamily) {
    if (law.scheme != Scheme::Euler) continue;
    double x = 0.0, v = 1.0, sum_new = 0.0, sum_old = 0.0, vk = 1.0;
    for (int i = 0; i < 60; ++i) {
      sum_old += vk;
      vk *= phi;
      sum_new += vk;
      advance(law, phi, h, 0.0, x, v);
    }
    INFO(law_key(law));
    CHECK(v == Approx(vk).epsilon(1e-13));
    const bool moves_with_old =
        law.position == PositionUpdate::Explicit || law.damping == DampingOrder::AfterPosition;
    const double expected = h * (moves_with_old ? sum_old : sum_new);
    CHECK(x == Approx(expected).epsilon(1e-13));
  }
}

// RK4 without damping is exact for a constant acceleration: x is quadratic in t.
TEST_CASE("law family: RK4 is exact for a constant acceleration", "[law][reference]") {
  const long double h = 0.01L, x0 = 10.0L, v0 = 3.0L;
  const int n = 500;
  long double x = x0, v = v0;
  const auto a = [](long double, long double) { return -9.8L; };
  for (int i = 0; i < n; ++i) advance_rk4(0.0L, h, a, x, v);
  const long double t = n * h;
  CHECK(std::abs(static_cast<double>(x - (x0 + v0 * t - 4.9L * t * t))) < 1e-13);  // 3.6e-15
  CHECK(std::abs(static_cast<double>(v - (v0 - 9.8L * t))) < 1e-13);
}

// Damping alone: each step keeps R(u) of the velocity, u = k*h, and moves the position by
// h*v*(1 - u/2 + u^2/6 - u^3/24) = h*v*T(u) (the stages' mean velocity); R = exp(-u) + O(u^5).
TEST_CASE("law family: RK4 decays a velocity by its stability polynomial", "[law][reference]") {
  const double k = 1.5, h = 0.1, u = k * h;
  const double r = 1 - u + u * u / 2 - u * u * u / 6 + u * u * u * u / 24;
  CHECK(rk4_decay(u) == Approx(r).epsilon(1e-15));
  double x = 0.0, v = 1.0, x_closed = 0.0, v_closed = 1.0;
  const auto none = [](double, double) { return 0.0; };
  for (int i = 0; i < 40; ++i) {
    advance_rk4(k, h, none, x, v);
    x_closed += h * v_closed * rk4_gain(u);
    v_closed *= r;
  }
  CHECK(v == Approx(v_closed).epsilon(1e-14));
  CHECK(x == Approx(x_closed).epsilon(1e-14));
  // Fourth order: one step's decay differs from exp(-u) by u^5/120 to leading order.
  CHECK(std::exp(-u) - r == Approx(-std::pow(u, 5) / 120).epsilon(0.15));
}

// On a spring x'' = -w^2*x the error after a fixed time falls 16-fold per halving of h.
TEST_CASE("law family: RK4 converges at fourth order on a spring", "[law][reference]") {
  const double w = 3.0, t_end = 2.0;
  auto error = [&](int steps) {
    const double h = t_end / steps;
    double x = 1.0, v = 0.0;
    const auto a = [&](double xs, double) { return -w * w * xs; };
    for (int i = 0; i < steps; ++i) advance_rk4(0.0, h, a, x, v);
    return std::abs(x - std::cos(w * t_end));
  };
  const double p1 = std::log2(error(200) / error(400)), p2 = std::log2(error(400) / error(800));
  CHECK(p1 == Approx(4.0).margin(0.1));  // measured 4.058 (w*h = 0.03 -> 0.015)
  CHECK(p2 == Approx(4.0).margin(0.1));  // measured 4.030
}

TEST_CASE("law family: six distinct members, each named by a key that parses back", "[law]") {
  CHECK(std::size(kLawFamily) == 6);
  CHECK(order_of(kRungeKutta4) == 4);
  CHECK(order_of(Law{DampingOrder::BeforeForces}) == 1);
  CHECK(law_key(kRungeKutta4) == "rk4");
  for (Law law : kLawFamily) CHECK(parse_law_key(law_key(law)) == law);
  CHECK(parse_law_key("after-position/explicit") ==
        Law{DampingOrder::AfterPosition, PositionUpdate::Explicit});
  CHECK_FALSE(parse_law_key("sideways").has_value());
  CHECK(to_string(Law{DampingOrder::BeforeForces}) == "v = phi*v + a*h; x += h*v");
}

}  // namespace
}  // namespace dropcheck

TEST_CASE("law family: two members' difference is named by what they differ in", "[law]") {
  const dropcheck::Law ours = dropcheck::DampingOrder::AfterForces,
                       bullet = dropcheck::DampingOrder::BeforeForces;
  const dropcheck::Law ode = dropcheck::DampingOrder::AfterPosition;
  const dropcheck::Law chipmunk{dropcheck::DampingOrder::BeforeForces,
                                dropcheck::PositionUpdate::Explicit};
  CHECK(dropcheck::law_difference(ours, ours).empty());
  CHECK(dropcheck::law_difference(ours, bullet) == "damping-order");
  CHECK(dropcheck::law_difference(bullet, ode) == "damping-order");
  CHECK(dropcheck::law_difference(bullet, chipmunk) == "position-update");
  CHECK(dropcheck::law_difference(ours, chipmunk) == "damping-order + position-update");
  // With the explicit position update, damping after the position is damping after the forces.
  const dropcheck::Law explicit_after{dropcheck::DampingOrder::AfterForces,
                                      dropcheck::PositionUpdate::Explicit};
  CHECK(dropcheck::law_difference(explicit_after,
                                  dropcheck::Law{dropcheck::DampingOrder::AfterPosition,
                                                 dropcheck::PositionUpdate::Explicit})
            .empty());
}

TEST_CASE("law family: without damping the damping order is no difference", "[law]") {
  const dropcheck::Law ours = dropcheck::DampingOrder::AfterForces;
  const dropcheck::Law chipmunk{dropcheck::DampingOrder::BeforeForces,
                                dropcheck::PositionUpdate::Explicit};
  CHECK(dropcheck::law_difference(ours, dropcheck::DampingOrder::BeforeForces, false).empty());
  CHECK(dropcheck::law_difference(ours, chipmunk, false) == "position-update");
}

TEST_CASE("law family: RK4 against an Euler member differs in scheme", "[law]") {
  const dropcheck::Law ours = dropcheck::DampingOrder::AfterForces;
  CHECK(dropcheck::law_difference(ours, dropcheck::kRungeKutta4) == "scheme");
  CHECK(dropcheck::law_difference(dropcheck::kRungeKutta4, dropcheck::kRungeKutta4).empty());
}

TEST_CASE("law family: the error-controlled member is declared, never fitted, has no order in h",
          "[law]") {
  using namespace dropcheck;
  CHECK(law_key(kErrorControlled) == "error-controlled");
  CHECK(parse_law_key("error-controlled") == kErrorControlled);
  CHECK(order_of(kErrorControlled) == 0);
  CHECK(std::find(std::begin(kLawFamily), std::end(kLawFamily), kErrorControlled) ==
        std::end(kLawFamily));
  CHECK(law_difference(kErrorControlled, Law{DampingOrder::AfterForces}) == "scheme");
  CHECK(law_difference(kErrorControlled, kErrorControlled).empty());
}
