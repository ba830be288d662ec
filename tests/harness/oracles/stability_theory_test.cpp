// Tests harness/oracles/stability_theory.cpp: the spring's stability edge under each law against
// theory (drag-free, with world damping, RK4's stability polynomial) and against the iterated step
// of each law, and the edge the step search finds on the engines (drag moves it up after the
// forces, down after the position).
#include "harness/oracles/stability_theory.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "harness/core/registry.hpp"
#include "harness/study/stability_search.hpp"
#include "tests/faulty_engine.hpp"

using namespace dropcheck;
using testing::engine_available;
using testing::registry_factory;

namespace {

// The stiff spring of scenarios/extreme/stiff_spring.toml: w = sqrt(3600/1) = 60 rad/s.
constexpr double kOmega = 60.0;

// The stiff spring (w = 60 rad/s, 5 cm from its anchor) built in code, with world damping k and a
// dashpot c, run 10 s at 1/40.
Scene spring_scene(double k, double dashpot) {
  Scene s;
  s.name = "spring";
  s.duration = 10.0;
  s.timestep = Timestep{1.0 / 40.0, "1/40"};
  s.timesteps = {s.timestep};
  s.world.gravity = Vec3(0.0, -9.8, 0.0);
  s.world.damping_rate = k;
  Body b;
  b.name = "bob";
  b.position = Vec3(0.0, 9.95, 0.0);
  s.bodies.push_back(b);
  s.forces.push_back(Force{{0}, Spring{Vec3(0.0, 10.0, 0.0), kOmega * kOmega, dashpot, 0.0}});
  return s;
}

// The first h > 0 where f(h) = (w*h)^2 - rhs(h) turns positive, by a 0.1% walk and bisection.
template <typename Rhs>
double first_edge(Rhs rhs) {
  auto f = [&](double h) { return kOmega * kOmega * h * h - rhs(h); };
  double hi = 1e-4;
  while (f(hi) < 0.0) hi *= 1.001;
  double lo = hi / 1.001;
  for (int i = 0; i < 200; ++i) (f(0.5 * (lo + hi)) < 0.0 ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

}  // namespace

TEST_CASE(
    "Stability: with world damping the edge moves up after the forces and down after the position",
    "[stability][theory]") {
  // Damping after the forces (ours): v_{n+1} = phi*(v_n - w^2*h*x_n), x_{n+1} = x_n + h*v_{n+1},
  // phi = exp(-k*h). In matrix form [x v]' = [[1 - phi*w^2*h^2, phi*h], [-phi*w^2*h, phi]] [x v],
  // trace 1 + phi - phi*w^2*h^2, determinant phi: z^2 - (1 + phi - phi*w^2*h^2)*z + phi = 0.
  // Jury: |phi| < 1 holds; P(1) = phi*w^2*h^2 > 0 holds; P(-1) = 2*(1 + phi) - phi*w^2*h^2 > 0,
  // i.e.
  //   |1 + phi - phi*w^2*h^2| < 1 + phi  <=>  w*h < sqrt(2*(1 + phi)/phi) = sqrt(2*(1 + exp(k*h))).
  // Damping after the position (ODE: u = v - w^2*h*x, x' = x + h*u, v' = phi*u) or before the
  // forces (Bullet: v' = phi*v - w^2*h*x, x' = x + h*v') has matrix trace 1 + phi - w^2*h^2 and
  // determinant phi: stable iff w*h < sqrt(2*(1 + phi)) = sqrt(2*(1 + exp(-k*h))), below 2.
  // With k = 20 1/s and w = 60 rad/s: ours' edge h = 0.0433238 s (w*h = 2.599, phi = 0.420),
  // ODE's and Bullet's 0.0293965 s (w*h = 1.764).
  const double k = 20.0;
  const double after_forces = first_edge([&](double h) { return 2.0 * (1.0 + std::exp(k * h)); });
  const double after_position =
      first_edge([&](double h) { return 2.0 * (1.0 + std::exp(-k * h)); });
  CHECK(after_forces == Approx(0.0433238).epsilon(1e-5));
  CHECK(after_position == Approx(0.0293965).epsilon(1e-5));
  const Scene scene = spring_scene(k, 0.0);
  CHECK(theory_max_dt(scene, DampingOrder::AfterForces).value() ==
        Approx(after_forces).epsilon(1e-9));
  CHECK(theory_max_dt(scene, DampingOrder::AfterPosition).value() ==
        Approx(after_position).epsilon(1e-9));
  CHECK(theory_max_dt(scene, DampingOrder::BeforeForces).value() ==
        Approx(after_position).epsilon(1e-9));

  // Measured: ours-f64 0.0433159 (-0.02%); ode and bullet 0.0293701 (-0.09%).
  const std::vector<std::pair<std::string, double>> expected = {
      {"ours-f64", after_forces}, {"ode", after_position}, {"bullet", after_position}};
  for (const auto& [name, edge] : expected) {
    if (!engine_available(name)) continue;
    const StepSearch s =
        search_max_stable_dt(registry_factory(name), scene, scene.timestep.seconds);
    INFO(name << ": max_stable_dt " << s.max_stable_dt << " vs theory " << edge);
    CHECK(std::abs(s.max_stable_dt / edge - 1.0) < 0.01);
  }
}

TEST_CASE("Stability: the spring theory matches the iterated step matrix of each law",
          "[stability][theory]") {
  // Iterates each law's exact step (harness/oracles/stability_theory.cpp) for 4000 steps from a
  // unit displacement at 0.5% inside and outside the predicted edge: inside stays below 1e3 x the
  // start energy (the discrete ellipse's flattening), outside passes 1e6 x.
  const std::vector<SpringModel> springs = {
      {60.0, 0.0, 0.0}, {60.0, 0.0, 20.0}, {60.0, 6.0, 20.0}, {10.0, 3.0, 1.2}, {60.0, 30.0, 0.0}};
  for (DampingOrder law :
       {DampingOrder::AfterForces, DampingOrder::BeforeForces, DampingOrder::AfterPosition}) {
    for (const SpringModel& m : springs) {
      const double edge = spring_max_stable_dt(law, m);
      for (double h : {edge * 0.995, edge * 1.005}) {
        const double phi = std::exp(-m.k * h);
        double x = 1.0, v = 0.0, peak = 0.0;
        for (int n = 0; n < 4000; ++n) {
          const double a = -m.omega * m.omega * x - m.gamma * v;
          if (law == DampingOrder::AfterForces) v = phi * (v + h * a), x += h * v;
          if (law == DampingOrder::BeforeForces) v = phi * v + h * a, x += h * v;
          if (law == DampingOrder::AfterPosition) v += h * a, x += h * v, v *= phi;
          peak = std::max(peak, (v * v + m.omega * m.omega * x * x) / (m.omega * m.omega));
        }
        INFO(to_string(law) << " w " << m.omega << " gamma " << m.gamma << " k " << m.k << " h "
                            << h);
        CHECK((h < edge ? peak < 1e3 : peak > 1e6));
      }
    }
  }
}

TEST_CASE("Stability: RK4's edges are its stability polynomial's, on a spring and on drag alone",
          "[stability][theory]") {
  // Undamped: h*M has eigenvalues +-i*w*h and |R(i*y)|^2 = 1 - y^6/72 + y^8/576 <= 1 iff
  // y <= sqrt(8): the edge is w*h = 2*sqrt(2).
  const SpringModel undamped{60.0, 0.0, 0.0};
  CHECK(spring_max_stable_dt(kRungeKutta4, undamped) ==
        Approx(2.0 * std::sqrt(2.0) / 60.0).epsilon(1e-9));
  // Drag alone: R(u) = 1 - u + u^2/2 - u^3/6 + u^4/24 returns to 1 at u = 2.7853.
  CHECK(rk4_decay(kRk4DampingEdge) == Approx(1.0).epsilon(1e-9));
  CHECK(damping_step_stable(kRungeKutta4, 20.0, 0.99 * kRk4DampingEdge / 20.0));
  CHECK_FALSE(damping_step_stable(kRungeKutta4, 20.0, 1.01 * kRk4DampingEdge / 20.0));
  CHECK(damping_step_stable(DampingOrder::AfterForces, 20.0, 1.0));
  // Each predicted edge against the iterated RK4 step (advance_rk4), 0.5% either side.
  const std::vector<SpringModel> springs = {
      {60.0, 0.0, 0.0}, {60.0, 0.0, 20.0}, {60.0, 6.0, 20.0}, {10.0, 3.0, 1.2}, {60.0, 30.0, 0.0}};
  for (const SpringModel& m : springs) {
    const double edge = spring_max_stable_dt(kRungeKutta4, m);
    for (double h : {edge * 0.995, edge * 1.005}) {
      double x = 1.0, v = 0.0, peak = 0.0;
      const auto a = [&](double xs, double vs) { return -m.omega * m.omega * xs - m.gamma * vs; };
      for (int n = 0; n < 4000; ++n) {
        advance_rk4(m.k, h, a, x, v);
        peak = std::max(peak, (v * v + m.omega * m.omega * x * x) / (m.omega * m.omega));
      }
      INFO("w " << m.omega << " gamma " << m.gamma << " k " << m.k << " h " << h);
      CHECK((h < edge ? peak < 1e3 : peak > 1e6));
    }
  }
}
