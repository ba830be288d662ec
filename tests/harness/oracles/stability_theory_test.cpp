// Tests harness/oracles/stability_theory.cpp: the spring's stability edge under each member of the
// law family against closed forms (2/omega undamped, 2*sqrt(2)/omega for RK4, the Jury conditions
// with drag and a dashpot), against the iterated step of each law, and against the edge the step
// search finds on the engines (drag moves it up after the forces, down after the position).
#include "harness/oracles/stability_theory.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
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

namespace {

// The step matrix of one law on the spring y'' = -w^2*y - gamma*y' (drag k where the law puts it),
// read off the law's own update applied to the unit states (y, v) = (1, 0) and (0, 1), and its
// eigenvalues from z^2 - trace*z + det = 0 in complex arithmetic.
std::pair<std::complex<double>, std::complex<double>> step_eigenvalues(Law law,
                                                                       const SpringModel& m,
                                                                       double h) {
  double col[2][2];
  for (int j = 0; j < 2; ++j) {
    double x = j == 0 ? 1.0 : 0.0, v = j == 0 ? 0.0 : 1.0;
    const auto accel = [&](double xs, double vs) { return -m.omega * m.omega * xs - m.gamma * vs; };
    if (law.scheme == Scheme::RK4) {
      advance_rk4(m.k, h, accel, x, v);
    } else {
      const double a = accel(x, v);  // the harness's force from the start-of-step state
      advance(law, std::exp(-m.k * h), h, a, x, v);
    }
    col[j][0] = x, col[j][1] = v;
  }
  const double trace = col[0][0] + col[1][1], det = col[0][0] * col[1][1] - col[1][0] * col[0][1];
  const std::complex<double> root = std::sqrt(std::complex<double>(trace * trace - 4.0 * det));
  return {(trace + root) / 2.0, (trace - root) / 2.0};
}

}  // namespace

TEST_CASE(
    "the spring's edge with a dashpot is (w*h)^2 + 2*gamma*h = 4, gamma/w^2 for forward Euler",
    "[stability][theory]") {
  // Without drag (phi = 1) every semi-implicit order has determinant 1 - gamma*h and A = (w*h)^2;
  // Jury's P(-1) > 0 gives (w*h)^2 + 2*gamma*h < 4, whose root is h = (sqrt(gamma^2 + 4*w^2) -
  // gamma)/w^2. Forward Euler multiplies the eigenvalue lambda of the continuous system by 1 +
  // h*lambda: |1 + h*lambda|^2 = 1 - gamma*h + (w*h)^2 <= 1 iff h <= gamma/w^2, and undamped (gamma
  // = 0) no step is stable.
  for (const SpringModel& m :
       {SpringModel{60.0, 6.0, 0.0}, SpringModel{10.0, 3.0, 0.0}, SpringModel{10.0, 19.0, 0.0}}) {
    const double w2 = m.omega * m.omega;
    const double semi = (std::sqrt(m.gamma * m.gamma + 4.0 * w2) - m.gamma) / w2;
    INFO("w " << m.omega << " gamma " << m.gamma);
    for (DampingOrder order :
         {DampingOrder::AfterForces, DampingOrder::BeforeForces, DampingOrder::AfterPosition}) {
      CHECK(spring_max_stable_dt(order, m) == Approx(semi).epsilon(1e-9));
      CHECK(spring_max_stable_dt(Law(order, PositionUpdate::Explicit), m) ==
            Approx(m.gamma / w2).epsilon(1e-9));
    }
  }
  // w = 60 rad/s with a dashpot of 6 1/s: the edge falls from 2/w = 0.0333 s to 0.0317083 s.
  CHECK(spring_max_stable_dt(DampingOrder::AfterForces, {60.0, 6.0, 0.0}) ==
        Approx(0.0317083).epsilon(1e-6));
  CHECK(spring_max_stable_dt(Law(DampingOrder::AfterForces, PositionUpdate::Explicit),
                             {60.0, 0.0, 0.0}) == 0.0);
}

TEST_CASE("one step of each law turns the spring by the angle and modulus of its step matrix",
          "[stability][theory]") {
  // Undamped semi-implicit Euler: trace 2 - (w*h)^2 and determinant 1, so the eigenvalues are
  // exp(+-i*theta) with cos(theta) = 1 - (w*h)^2/2, i.e. theta = 2*asin(w*h/2): kept to the last
  // digits at w*h = 1e-4, where acos(1 - 5e-9) would keep half of them.
  const SpringModel undamped{60.0, 0.0, 0.0};
  for (double wh : {1e-4, 0.5, 1.875}) {
    const auto r = spring_step_rotation(DampingOrder::AfterForces, undamped, wh / 60.0);
    REQUIRE(r.has_value());
    CHECK(r->rho == Approx(1.0).epsilon(1e-14));
    CHECK(r->theta == Approx(2.0 * std::asin(wh / 2.0)).epsilon(1e-12));
  }
  // Every law, with drag and a dashpot: modulus and angle of the eigenvalues of its step matrix.
  const std::vector<Law> laws = {DampingOrder::AfterForces,
                                 DampingOrder::BeforeForces,
                                 DampingOrder::AfterPosition,
                                 Law(DampingOrder::AfterForces, PositionUpdate::Explicit),
                                 Law(DampingOrder::BeforeForces, PositionUpdate::Explicit),
                                 kRungeKutta4};
  for (const Law& law : laws) {
    for (const SpringModel& m : {SpringModel{60.0, 6.0, 20.0}, SpringModel{10.0, 3.0, 1.2}}) {
      const double h = 0.5 / m.omega;
      const auto [z, conj] = step_eigenvalues(law, m, h);
      const auto r = spring_step_rotation(law, m, h);
      INFO(to_string(law) << " w " << m.omega << " gamma " << m.gamma << " k " << m.k);
      REQUIRE(r.has_value());
      CHECK(r->rho == Approx(std::abs(z)).epsilon(1e-12));
      CHECK(r->theta == Approx(std::abs(std::arg(z))).epsilon(1e-12));
    }
  }
  // With drag alone the determinant is phi = exp(-k*h) for every semi-implicit order: the
  // amplitude shrinks by sqrt(phi) = exp(-k*h/2) per step.
  CHECK(spring_step_rotation(DampingOrder::BeforeForces, {60.0, 0.0, 20.0}, 0.01)->rho ==
        Approx(std::exp(-0.1)).epsilon(1e-12));
  // Beyond the edge (w*h = 2.1) the eigenvalues are real: no rotation; nor for a scheme without a
  // fixed step.
  CHECK_FALSE(spring_step_rotation(DampingOrder::AfterForces, undamped, 2.1 / 60.0).has_value());
  CHECK_FALSE(spring_step_rotation(kErrorControlled, undamped, 0.01).has_value());
}

TEST_CASE("theory_max_dt is the smallest edge over the dynamic bodies' combined linear springs",
          "[stability][theory]") {
  Scene s;
  s.name = "springs";
  s.duration = 1.0;
  auto body = [&](const std::string& name, double mass, bool is_static = false) {
    Body b;
    b.name = name;
    b.mass = mass;
    b.is_static = is_static;
    b.position = Vec3(3.0 * static_cast<double>(s.bodies.size()), 0.0, 0.0);
    s.bodies.push_back(b);
    return s.bodies.size() - 1;
  };
  auto spring = [&](std::size_t i, double stiffness, double damping, double rest = 0.0) {
    s.forces.push_back(Force{{i}, Spring{s.bodies[i].position, stiffness, damping, rest}});
  };
  const std::size_t pair = body("pair", 2.0);  // two springs: w^2 = 7200/2, gamma = 12/2
  spring(pair, 3600.0, 4.0);
  spring(pair, 3600.0, 8.0);
  const std::size_t soft = body("soft", 1.0);  // w = 30 rad/s
  spring(soft, 900.0, 0.0);
  const std::size_t rope = body("rope", 1.0);  // a rest length: nonlinear, no single w
  spring(rope, 1e6, 0.0, 0.5);
  const std::size_t wall = body("wall", 1.0, true);  // static: never moves, whatever acts on it
  spring(wall, 1e8, 0.0);
  body("free", 1.0);

  const std::optional<SpringModel> p = body_spring(s, pair);
  REQUIRE(p.has_value());
  CHECK(p->omega == Approx(60.0).epsilon(1e-15));
  CHECK(p->gamma == Approx(6.0).epsilon(1e-15));
  CHECK(p->k == 0.0);
  CHECK(body_spring(s, soft)->omega == Approx(30.0).epsilon(1e-15));
  CHECK_FALSE(body_spring(s, rope).has_value());
  CHECK_FALSE(body_spring(s, 4).has_value());  // free flight

  // The pair's edge (sqrt(36 + 4*3600) - 6)/3600 = 0.0317083 s is below the soft spring's 2/30.
  const double pair_edge = (std::sqrt(36.0 + 4.0 * 3600.0) - 6.0) / 3600.0;
  CHECK(theory_max_dt(s, DampingOrder::AfterForces).value() == Approx(pair_edge).epsilon(1e-9));
  // RK4 under drag k = 100 1/s: the free bodies' damping edge 2.7853/100 s is the smallest.
  s.world.damping_rate = 100.0;
  CHECK(theory_max_dt(s, kRungeKutta4).value() == Approx(kRk4DampingEdge / 100.0).epsilon(1e-12));
  CHECK_FALSE(theory_max_dt(s, kErrorControlled).has_value());
  // Free flight alone bounds no Euler step.
  s.forces.clear();
  CHECK_FALSE(theory_max_dt(s, DampingOrder::BeforeForces).has_value());
}
