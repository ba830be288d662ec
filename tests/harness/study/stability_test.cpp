// Tests the stability files (harness/oracles/stability_theory.cpp, harness/judge/stability_*.cpp,
// harness/study/stability_*.cpp): the spring's stability edge against theory (drag-free and with
// drag), each failure classification on a purpose-built scene, and every extreme scene on every
// engine that can run it. A test double (FaultyEngine) places failures where the real engines do
// not have them.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include "harness/core/registry.hpp"
#include "harness/judge/stability_classify.hpp"
#include "harness/oracles/stability_theory.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/stability_search.hpp"

using Catch::Matchers::Contains;
using namespace dropcheck;

namespace {

Scene extreme(const std::string& stem) {
  return load_scene(std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/extreme/" + stem + ".toml");
}

bool available(const std::string& name) {
  return make_engine(name) != nullptr;
}

EngineFactory factory(const std::string& name) {
  return [name] { return make_engine(name); };
}

// A semi-implicit Euler engine like ours (v = phi*(v + (g + F/m)*h); x += h*v; static bodies stay)
// that claims contacts but has none, and injects one fault from step `at` on.
class FaultyEngine final : public Engine {
 public:
  enum class Fault { none, nan, error, clamp, stop, double_speed };
  FaultyEngine(Fault fault, std::int64_t at) : fault_(fault), at_(at) {}

  EngineInfo info() const override {
    EngineInfo i;
    i.name = "faulty";
    i.capabilities.contacts = true;
    return i;
  }
  void load(const Scene& scene, double h) override {
    scene_ = scene;
    h_ = h;
    n_ = 0;
    states_.clear();
    for (const Body& b : scene.bodies) states_.push_back({b.position, b.velocity});
  }
  void set_forces(std::span<const Vec3> f) override { forces_.assign(f.begin(), f.end()); }
  void step() override {
    if (++n_ >= at_ && fault_ == Fault::error) throw EngineError("solver gave up");
    for (std::size_t i = 0; i < states_.size(); ++i) {
      if (scene_.bodies[i].is_static) continue;
      BodyState& s = states_[i];
      s.velocity = decay_per_step(scene_, h_) *
                   (s.velocity + (scene_.world.gravity + forces_[i] / scene_.bodies[i].mass) * h_);
      if (n_ >= at_ && fault_ == Fault::stop) s.velocity.setZero();  // "sleeping"
      if (n_ >= at_ && fault_ == Fault::double_speed) s.velocity *= 2.0;
      if (n_ >= at_ && fault_ == Fault::nan)
        s.velocity.x() = std::numeric_limits<double>::quiet_NaN();
      s.position += h_ * s.velocity;
    }
  }
  void read(std::span<BodyState> out) const override {
    std::copy(states_.begin(), states_.end(), out.begin());
  }
  bool speed_clamped() const override { return fault_ == Fault::clamp && n_ >= at_; }

 private:
  Fault fault_;
  std::int64_t at_;
  Scene scene_;
  double h_ = 0.0;
  std::int64_t n_ = 0;
  std::vector<BodyState> states_;
  std::vector<Vec3> forces_;
};

Verdict classify_faulty(const Scene& scene, FaultyEngine::Fault fault, std::int64_t at) {
  FaultyEngine engine(fault, at);
  return classify_run(scene, run_scene(engine, scene, scene.timestep.seconds), Scalar::f64);
}

// The stiff spring of scenarios/extreme/stiff_spring.toml: w = sqrt(3600/1) = 60 rad/s.
constexpr double kOmega = 60.0;

}  // namespace

TEST_CASE(
    "Stability: bisection finds the drag-free spring's edge h = 2/omega for ours-f64 within 1%",
    "[stability][theory]") {
  const Scene scene = extreme("stiff_spring");
  const StepSearch s = search_max_stable_dt(factory("ours-f64"), scene, scene.timestep.seconds);
  const double edge = 2.0 / kOmega;
  // Measured: max_stable_dt 0.033303 (-0.09%), first unstable 0.0333481 (+0.05%), 11 probes.
  CHECK(std::abs(s.max_stable_dt / edge - 1.0) < 0.01);
  CHECK(s.max_stable_dt <= edge);
  CHECK(s.min_unstable_dt >= edge);
  REQUIRE(s.limit.has_value());
  CHECK(*s.limit == FailureMode::unbounded_growth);
  CHECK(theory_max_dt(scene, DampingOrder::AfterForces).value() == Approx(edge).epsilon(1e-12));
}

TEST_CASE(
    "Stability: every engine's bisection finds 2/omega on the drag-free spring, Box2D just below "
    "it",
    "[stability][theory]") {
  // Without damping every law reduces to v' = v - w^2*h*x, x' = x + h*v': stable iff w*h < 2.
  // Measured (10 s horizon, bisection to 0.2%): ours, ours-f64, bullet, ode, mujoco bracket the
  // edge [0.033303, 0.0333481] (MuJoCo fails above it with its own "bad qacc" warning: an engine
  // error); box2d stops at 0.033258 (-0.23%): near the edge the discrete oscillation's speed
  // swells to sqrt(1/(1 - w*h/2)) times the physical one and passes Box2D's 2 m per step limit.
  // An engine that moves the position with the step-start velocity (Chipmunk) is forward Euler
  // on the spring: |z|^2 = 1 + (w*h)^2 at every step, so no step is stable, as the theory says.
  const Scene scene = extreme("stiff_spring");
  const double edge = 2.0 / kOmega;
  for (const std::string& name : available_engine_names()) {
    if (!make_engine(name)->cannot_run(scene).empty()) continue;  // simbody-rkm: springs
    const EngineInfo info = make_engine(name)->info();
    const StepSearch s = search_max_stable_dt(factory(name), scene, scene.timestep.seconds);
    INFO(name << ": max_stable_dt " << s.max_stable_dt << ", first unstable " << s.min_unstable_dt);
    if (info.law.scheme == Scheme::RK4) {  // RK4's edge on the imaginary axis: w*h = 2*sqrt(2)
      CHECK(std::abs(s.max_stable_dt / (std::sqrt(2.0) * edge) - 1.0) < 0.01);
      continue;
    }
    if (info.law.position == PositionUpdate::Explicit) {
      CHECK(std::isnan(s.max_stable_dt));
      CHECK(theory_max_dt(scene, info.law).value() == 0.0);
      CHECK(s.limit == FailureMode::unbounded_growth);
      continue;
    }
    CHECK(std::abs(s.max_stable_dt / edge - 1.0) < 0.01);
    if (name != "box2d") CHECK(s.min_unstable_dt >= edge);
    if (name == "box2d") CHECK(s.limit == FailureMode::clamped);
  }
}

namespace {

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
    if (!available(name)) continue;
    const StepSearch s = search_max_stable_dt(factory(name), scene, scene.timestep.seconds);
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

TEST_CASE("Stability: a stable run has no failure", "[stability][classify]") {
  const Scene scene = extreme("stiff_spring");  // w*h = 1.875 at its own step
  auto engine = make_engine("ours-f64");
  const Verdict v =
      classify_run(scene, run_scene(*engine, scene, scene.timestep.seconds), Scalar::f64);
  CHECK(v.stable());
}

TEST_CASE("Stability: a NaN state is classified NaN/Inf and an engine's error as an engine error",
          "[stability][classify]") {
  const Scene scene = extreme("large_step");
  const Verdict nan = classify_faulty(scene, FaultyEngine::Fault::nan, 7);
  REQUIRE_FALSE(nan.stable());
  CHECK(nan.failures.front().mode == FailureMode::non_finite);
  CHECK(nan.failures.front().step == 7);
  CHECK_THAT(nan.failures.front().what, Contains("NaN/Inf") && Contains("step 7"));
  const Verdict error = classify_faulty(scene, FaultyEngine::Fault::error, 3);
  REQUIRE_FALSE(error.stable());
  CHECK(error.failures.front().mode == FailureMode::engine_error);
  CHECK_THAT(error.failures.front().what, Contains("engine error at step 3: solver gave up"));
}

TEST_CASE("Stability: a spring stepped beyond omega*h = 2 is classified as unbounded growth",
          "[stability][classify]") {
  Scene scene = extreme("stiff_spring");
  const double h = 1.0 / 29.0;  // w*h = 2.069
  auto engine = make_engine("ours-f64");
  const Verdict v = classify_run(scene, run_scene(*engine, scene, h), Scalar::f64);
  REQUIRE_FALSE(v.stable());
  CHECK(v.failures.front().mode == FailureMode::unbounded_growth);
  CHECK_THAT(v.failures.front().what,
             Contains("body 'bob': oscillation energy") && Contains("omega*h = 2.069"));
}

TEST_CASE("Stability: free flight faster than any first-order law allows is unbounded growth",
          "[stability][classify]") {
  const Scene scene = extreme("apex_hang");  // net 1e-4 m/s^2, k = 0.1 1/s: terminal 1e-3 m/s
  const Verdict v = classify_faulty(scene, FaultyEngine::Fault::double_speed, 4);
  REQUIRE_FALSE(v.stable());
  CHECK(v.failures.front().mode == FailureMode::unbounded_growth);
  CHECK(v.failures.front().step == 7);  // ~1e-4 m/s doubled on steps 4..7 passes 1.01e-3 m/s
  CHECK_THAT(v.failures.front().what,
             Contains("body 'hover': speed") && Contains("(|a|/k)*kh/(1 - exp(-kh))"));
}

TEST_CASE("Stability: float positions at the tiny step are classified frozen, double ones move",
          "[stability][classify]") {
  const Scene scene = extreme("tiny_step");
  auto f32 = make_engine("ours");
  const Verdict v =
      classify_run(scene, run_scene(*f32, scene, scene.timestep.seconds), Scalar::f32);
  REQUIRE(v.failures.size() == 1);  // near_0 moves: float spacing at 0.01 m is 9.3e-10 m
  const Failure& f = v.failures.front();
  CHECK(f.mode == FailureMode::frozen);
  CHECK(f.body == "at_10m");
  CHECK(f.step == 1);
  CHECK_THAT(f.what, Contains("frozen at y = 10.000000 from step 1 to step 200") &&
                         Contains("v*h = 9.8e-10 m to 2e-07 m per step is below half the float "
                                  "spacing 4.8e-07 m at 10 m"));
  auto f64 = make_engine("ours-f64");
  CHECK(classify_run(scene, run_scene(*f64, scene, scene.timestep.seconds), Scalar::f64).stable());
}

TEST_CASE("Stability: a body an engine stops (sleeping) is frozen, held by the engine",
          "[stability][classify]") {
  const Scene scene = extreme("near_zero");  // |v| ~ 1e-6 m/s: below every sleeping threshold
  const Verdict v = classify_faulty(scene, FaultyEngine::Fault::stop, 100);
  REQUIRE_FALSE(v.stable());
  CHECK(v.failures.front().mode == FailureMode::frozen);
  CHECK(v.failures.front().step == 100);
  CHECK_THAT(v.failures.front().what, Contains("the engine held it"));
}

TEST_CASE("Stability: a body that passes through the thin floor is classified tunnelled",
          "[stability][classify]") {
  const Scene scene = extreme("thin_floor");
  const Verdict v =
      classify_faulty(scene, FaultyEngine::Fault::none, 0);  // claims contacts, has none
  REQUIRE_FALSE(v.stable());
  CHECK(v.failures.front().mode == FailureMode::tunnelled);
  CHECK(v.failures.front().step == 1);
  CHECK_THAT(v.failures.front().what, Contains("body 'bullet' ended below 'floor'") &&
                                          Contains("static") && Contains("3.34 m per step"));
  // Real engines with discrete collision (measured at 1/60: bullet, ode and mujoco tunnel; box2d's
  // continuous collision stops the cube on the floor).
  for (const char* name : {"bullet", "ode", "mujoco"}) {
    if (!available(name)) continue;
    auto engine = make_engine(name);
    const Verdict r = classify_run(scene, run_scene(*engine, scene, scene.timestep.seconds),
                                   engine->info().scalar);
    INFO(name);
    REQUIRE_FALSE(r.stable());
    CHECK(r.failures.front().mode == FailureMode::tunnelled);
  }
}

TEST_CASE("Stability: a clamped speed is classified speed clamped", "[stability][classify]") {
  const Scene scene = extreme("huge_gravity");
  const Verdict v = classify_faulty(scene, FaultyEngine::Fault::clamp, 5);
  REQUIRE_FALSE(v.stable());
  CHECK(v.failures.front().mode == FailureMode::clamped);
  CHECK_THAT(v.failures.front().what, Contains("on 26 of 30 steps, first at step 5"));
  if (!available("box2d")) {
    WARN("box2d not compiled in: its real speed clamp is not checked");
    return;
  }
  // Box2D moves a body at most 2 m per step: the 100 g faller passes 120 m/s at step 9 (measured).
  auto engine = make_engine("box2d");
  const Verdict b =
      classify_run(scene, run_scene(*engine, scene, scene.timestep.seconds), Scalar::f32);
  REQUIRE_FALSE(b.stable());
  CHECK(b.failures.front().mode == FailureMode::clamped);
  CHECK(b.failures.front().step == 9);
  CHECK_THAT(b.failures.front().what, Contains("body 'faller' moves 2 m per step (|v| = 120 m/s)"));
}

TEST_CASE(
    "Stability: every extreme scene runs on every engine that can run it without crashing the "
    "harness",
    "[stability][extreme]") {
  // Each scene at its own step, cut to its first 20000 steps (only long_run is longer: the report
  // and `dropcheck stability` run its whole hour) to keep this test short under sanitizers.
  std::vector<std::string> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(DROPCHECK_SOURCE_DIR "/scenarios/extreme"))
    if (entry.path().extension() == ".toml") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 12);
  for (const std::string& file : files) {
    const Scene full = load_scene(file);
    const double h = full.timestep.seconds;
    const Scene scene = scene_for_step(full, h, std::min(full.duration, 20000.0 * h));
    for (const std::string& name : available_engine_names()) {
      auto engine = make_engine(name);
      if (!engine->cannot_run(scene).empty()) continue;
      INFO(scene.name << " on " << name);
      RunOptions options;
      options.record_every = stability_record_every(step_count(scene, h));
      const Trajectory run = run_scene(*engine, scene, h, options);
      const Verdict v = classify_run(scene, run, engine->info().scalar);
      CHECK((run.status == RunStatus::ok || !v.stable()));  // a failed run is never called stable
      for (const Failure& f : v.failures) CHECK_FALSE(f.what.empty());
    }
  }
}

// Gazebo's tumbling box at h = 0.2 s (|w|*h = 1): the explicit gyroscopic member (ours-f64)
// pumps rotational energy far beyond what its angular momentum allows (|L|^2/(2*I_min) = 41.2 J
// against 8.55 J at the start), the linearly implicit one (ODE) stays within it; Bullet's turn is
// clamped to pi/4 per step (|w|*h = 1), which it reports. Measured with `dropcheck stability
// scenarios/gazebo_boxes_complex.toml`: ours, ours-f64 and MuJoCo stable up to h = 0.1547 s, ODE
// up to the 1 s cap.
TEST_CASE("a turning body whose rotational energy passes what its momentum allows is unstable",
          "[stability][rotation]") {
  Scene scene = load_scene(DROPCHECK_SOURCE_DIR "/scenarios/gazebo_boxes_complex.toml");
  for (const char* name : {"ours-f64", "bullet", "ode"}) {
    const Trajectory run = run_scene(*make_engine(name), scene, 0.2);
    const Verdict v = classify_run(scene, run, Scalar::f64);
    INFO(name << ": " << (v.stable() ? "stable" : v.failures[0].what));
    if (std::string(name) == "ours-f64") {
      // The growth shows steps before the state overflows to Inf/NaN (the severest failure).
      REQUIRE(v.failures.size() == 2);
      CHECK(v.failures[0].mode == FailureMode::non_finite);
      CHECK(v.failures[1].mode == FailureMode::unbounded_growth);
      CHECK(v.failures[1].step < v.failures[0].step);
      CHECK_THAT(v.failures[1].what, Contains("rotational energy") && Contains("exceeds 41.22 J"));
    } else if (std::string(name) == "bullet") {
      REQUIRE(v.failures.size() == 1);
      CHECK(v.failures[0].mode == FailureMode::clamped);
      CHECK_THAT(v.failures[0].what, Contains("turns by |w|*h = 1 rad per step"));
    } else {
      CHECK(v.stable());
    }
  }
}
