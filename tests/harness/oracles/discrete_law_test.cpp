// Tests harness/oracles/discrete_law.cpp: each DampingOrder law against its closed form.
//
// Constant acceleration a = g + F/m, b = a*h, decay phi per step, v0 and x0 given.
//   AfterForces:   v_{n+1} = phi*(v_n + b)
//     v_n = phi^n*v0 + phi*b*(1 - phi^n)/(1 - phi)
//     x_n = x0 + h*sum_{j=1..n} v_j = x0 + h*v0*G + h*phi*b/(1 - phi)*(n - G),  G = phi*(1 -
//     phi^n)/(1 - phi)
//   BeforeForces:  v_{n+1} = phi*v_n + b   (fixed point b/(1 - phi))
//     v_n = phi^n*v0 + b*(1 - phi^n)/(1 - phi)        (v0 = 0: v_n = a*h*(1 - phi^n)/(1 - phi))
//     x_n = x0 + h*v0*G + h*b/(1 - phi)*(n - G)
//   AfterPosition: v' = v_n + b; x_{n+1} = x_n + h*v'; v_{n+1} = phi*v'
//     v_n as AfterForces (the read-out velocity is damped last);
//     x_n = x0 + h*sum_{j=0..n-1}(v_j + b) = x0 + h*v0*G/phi + h*b/(1 - phi)*(n - G)
// So with v0 = 0 BeforeForces and AfterPosition have the same x_n, and AfterForces' displacement
// is phi times theirs (docs/engines.md section 2); with v0 != 0 BeforeForces damps v0 once more.
#include "harness/oracles/discrete_law.hpp"

#include <catch2/catch.hpp>
#include <cmath>

#include "harness/core/scene_loader.hpp"

namespace {

using dropcheck::DampingOrder;
using LD = long double;

// One axis of the closed forms above.
void closed_form(DampingOrder law, LD x0, LD v0, LD a, LD phi, LD h, int n, LD& x, LD& v) {
  const LD b = a * h, pn = std::pow(phi, LD(n)), G = phi * (1 - pn) / (1 - phi);
  switch (law) {
    case DampingOrder::AfterForces:
      v = pn * v0 + phi * b * (1 - pn) / (1 - phi);
      x = x0 + h * v0 * G + h * phi * b / (1 - phi) * (n - G);
      break;
    case DampingOrder::BeforeForces:
      v = pn * v0 + b * (1 - pn) / (1 - phi);
      x = x0 + h * v0 * G + h * b / (1 - phi) * (n - G);
      break;
    case DampingOrder::AfterPosition:
      v = pn * v0 + phi * b * (1 - pn) / (1 - phi);
      x = x0 + h * v0 * G / phi + h * b / (1 - phi) * (n - G);
      break;
  }
}

// A thrown cube of mass 2 with a constant force and the seed's damping rate, 3 s at 1/60.
const char* kThrown = R"(
duration = 3.0
[world]
gravity = [0.0, -9.8, 0.0]
linear_damping = 1.2121622213135165
[[body]]
name = "cube"
mass = 2.0
position = [1.0, 1.0, -1.0]
velocity = [3.0, 8.0, 0.5]
[[force]]
constant = [4.0, 1.0, -2.0]
)";

// Worst |x - closed form| over every step and axis of `law` on kThrown.
void worst_error(DampingOrder law, double& dx, double& dv) {
  const dropcheck::Scene s = dropcheck::parse_scene(kThrown, "thrown.toml");
  const double h = s.timestep.seconds;
  const dropcheck::Trajectory t = dropcheck::predict_discrete(law, s, h);
  const LD phi = std::exp(-LD(s.world.damping_rate) * LD(h));
  const dropcheck::Vec3 F(4.0, 1.0, -2.0);
  dx = dv = 0.0;
  for (std::size_t i = 0; i < t.samples(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const dropcheck::Body& b = s.bodies[0];
      LD x, v;
      closed_form(law, b.position[k], b.velocity[k], LD(s.world.gravity[k]) + LD(F[k]) / LD(b.mass),
                  phi, h, int(t.recorded[i]), x, v);
      dx = std::max(dx, double(std::fabs(t.at(i, 0).position[k] - x)));
      dv = std::max(dv, double(std::fabs(t.at(i, 0).velocity[k] - v)));
    }
  }
}

// Final height after 60 steps of docs/engines.md's scene (x0 = 10, v0 = 0, f = 0.98 at 1/60).
double engine_notes_height(DampingOrder law) {
  const dropcheck::Scene s = dropcheck::parse_scene(
      "duration = 1.0\n[world]\ngravity = [0.0, -9.8, 0.0]\nlinear_drag = 0.98\n"
      "[[body]]\nname = \"cube\"\nposition = [0.0, 10.0, 0.0]\n",
      "notes.toml");
  const dropcheck::Trajectory t = dropcheck::predict_discrete(law, s, 1.0 / 60.0);
  REQUIRE(t.recorded.back() == 60);
  return t.final_state(0).position.y();
}

}  // namespace

TEST_CASE("the AfterForces law matches its closed form with v0, a force and mass 2",
          "[discrete_law]") {
  double dx, dv;
  worst_error(DampingOrder::AfterForces, dx, dv);
  CHECK(dx < 1e-12);  // measured 8.8e-16
  CHECK(dv < 1e-12);  // measured 4.4e-16
}

TEST_CASE("the BeforeForces law matches its closed form with v0, a force and mass 2",
          "[discrete_law]") {
  double dx, dv;
  worst_error(DampingOrder::BeforeForces, dx, dv);
  CHECK(dx < 1e-12);  // measured 8.3e-16
  CHECK(dv < 1e-12);  // measured 4.4e-16
}

TEST_CASE("the AfterPosition law matches its closed form with v0, a force and mass 2",
          "[discrete_law]") {
  double dx, dv;
  worst_error(DampingOrder::AfterPosition, dx, dv);
  CHECK(dx < 1e-12);  // measured 8.7e-16
  CHECK(dv < 1e-12);  // measured 4.4e-16
}

TEST_CASE(
    "60 steps of each law reproduce docs/engines.md's 6.5878983508563724 and 6.5182636233228308",
    "[discrete_law]") {
  // The law iterates in long double from phi = exp(-k*h); the figures are double iterations with
  // f = 0.98: they agree to the rounding of the double iteration.
  CHECK(engine_notes_height(DampingOrder::AfterForces) ==
        Approx(6.5878983508563724).margin(1e-14));  // measured 0
  CHECK(engine_notes_height(DampingOrder::BeforeForces) ==
        Approx(6.5182636233228308).margin(1e-14));  // measured 1.8e-15
  CHECK(engine_notes_height(DampingOrder::AfterPosition) ==
        Approx(6.5182636233228308).margin(1e-14));  // measured 1.8e-15
}

TEST_CASE("the laws predict a static body stays where it is", "[discrete_law]") {
  const dropcheck::Scene s = dropcheck::parse_scene(
      "duration = 1.0\n[world]\ngravity = [0.0, -9.8, 0.0]\n"
      "[[body]]\nname = \"floor\"\nposition = [0.0, -0.5, 0.0]\nstatic = true\n"
      "[[body]]\nname = \"cube\"\nposition = [0.0, 10.0, 0.0]\n",
      "static.toml");
  const dropcheck::Trajectory t =
      dropcheck::predict_discrete(DampingOrder::BeforeForces, s, 1.0 / 60.0);
  CHECK(t.final_state(0).position == dropcheck::Vec3(0.0, -0.5, 0.0));
  CHECK(t.final_state(1).position.y() < 6.0);  // while the dynamic one falls
}
