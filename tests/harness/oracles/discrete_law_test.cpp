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

#include "harness/scene/scene_loader.hpp"
#include "tests/scene_texts.hpp"

namespace {

using dropcheck::DampingOrder;
using dropcheck::testing::body_text;
using dropcheck::testing::kEarth;
using dropcheck::testing::scene_head;
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
const std::string kThrown =
    scene_head("3.0", "", kEarth, "linear_damping = 1.2121622213135165\n") +
    body_text("cube", "[1.0, 1.0, -1.0]", "[3.0, 8.0, 0.5]", "mass = 2.0\n") +
    "[[force]]\nconstant = [4.0, 1.0, -2.0]\n";

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
      scene_head("1.0", "", kEarth, "linear_drag = 0.98\n") + body_text("cube", "[0.0, 10.0, 0.0]"),
      "notes.toml");
  const dropcheck::Trajectory t = dropcheck::predict_discrete(law, s, 1.0 / 60.0);
  REQUIRE(t.recorded.back() == 60);
  return t.final_state(0).position.y();
}

}  // namespace

TEST_CASE("each DampingOrder law matches its closed form with v0, a force and mass 2",
          "[discrete_law]") {
  // Measured worst |dx| and |dv| per law, each well inside 1e-12.
  struct Case {
    DampingOrder law;
    const char* measured;
  };
  const Case c = GENERATE(Case{DampingOrder::AfterForces, "dx 8.8e-16, dv 4.4e-16"},
                          Case{DampingOrder::BeforeForces, "dx 8.3e-16, dv 4.4e-16"},
                          Case{DampingOrder::AfterPosition, "dx 8.7e-16, dv 4.4e-16"});
  double dx, dv;
  worst_error(c.law, dx, dv);
  INFO(dropcheck::to_string(c.law) << " law (measured " << c.measured << ")");
  CHECK(dx < 1e-12);
  CHECK(dv < 1e-12);
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
  const dropcheck::Scene s =
      dropcheck::parse_scene(scene_head("1.0", "", kEarth) +
                                 body_text("floor", "[0.0, -0.5, 0.0]", "", "static = true\n") +
                                 body_text("cube", "[0.0, 10.0, 0.0]"),
                             "static.toml");
  const dropcheck::Trajectory t =
      dropcheck::predict_discrete(DampingOrder::BeforeForces, s, 1.0 / 60.0);
  CHECK(t.final_state(0).position == dropcheck::Vec3(0.0, -0.5, 0.0));
  CHECK(t.final_state(1).position.y() < 6.0);  // while the dynamic one falls
}

// RK4 with a constant a = g + F/m and damping k, u = k*h, q = a - k*v: the stages' velocities are
// v, v + h/2*q, v + h/2*q*(1 - u/2), v + h*q*(1 - u/2 + u^2/4), so one step is
//   v' = R(u)*v + h*T(u)*a,  x' = x + h*v + h^2/6*q*(3 - u + u^2/4)
// (harness/core/law.hpp). The oracle, which runs the four stages, must give this map's iterates.
TEST_CASE("the RK4 law matches its one-step closed form with v0, a force and mass 2",
          "[discrete_law]") {
  const dropcheck::Scene s = dropcheck::parse_scene(kThrown, "thrown.toml");
  const double h = s.timestep.seconds;
  const dropcheck::Trajectory t = dropcheck::predict_discrete(dropcheck::kRungeKutta4, s, h);
  const LD k = s.world.damping_rate, u = k * LD(h), hl = h;
  const dropcheck::Body& b = s.bodies[0];
  double dx = 0.0, dv = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    const LD a = LD(s.world.gravity[axis]) + LD(dropcheck::Vec3(4.0, 1.0, -2.0)[axis]) / 2.0L;
    LD x = b.position[axis], v = b.velocity[axis];
    for (std::size_t i = 0; i < t.samples(); ++i) {
      dx = std::max(dx, double(std::fabs(t.at(i, 0).position[axis] - x)));
      dv = std::max(dv, double(std::fabs(t.at(i, 0).velocity[axis] - v)));
      const LD q = a - k * v;
      x += hl * v + hl * hl / 6 * q * (3 - u + u * u / 4);
      v = dropcheck::rk4_decay(u) * v + hl * dropcheck::rk4_gain(u) * a;
    }
  }
  CHECK(dx < 1e-12);  // measured 8.2e-16 (the states are read out as double)
  CHECK(dv < 1e-12);  // measured 4.4e-16
}
