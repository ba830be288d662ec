// Tests adapters/bullet.cpp: Bullet 3.24 (Debian's float64 build by default) through the Engine
// interface.
//
// References: oracle 2 (harness/oracles/discrete_law.hpp, Bullet's law v = phi*v + a*h; x += h*v
// iterated in long double) for free flight; harness/oracles/landing.hpp (continuous first-contact
// time, the law's first-contact step, geometric rest height) for landing; docs/engines.md sections
// 2 and 5 for the figures reproduced here. Set DROPCHECK_MEASURE=1 to print the measured figures.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>

#include "harness/core/registry.hpp"
#include "harness/core/runner.hpp"
#include "harness/core/scene_loader.hpp"
#include "harness/measure/checks.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/oracles/landing.hpp"

using namespace dropcheck;

namespace {

const char* const kFreeFlightScenes[] = {"seed_part3", "free_fall", "free_fall_drag", "wind",
                                         "throw_up"};

Scene scenario(const std::string& name) {
  return load_scene(std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/" + name + ".toml");
}

bool measuring() {
  return std::getenv("DROPCHECK_MEASURE") != nullptr;
}

// Rounding of a run against its own law (m, m/s). Double: measured worst 1.8e-13 m and 1.1e-13 m/s
// (seed_part3 at 1/240); at 1/60 2.1e-14 m, at 1/30 1.4e-14 m. Float build
// (DROPCHECK_BULLET_PRECISION=float): measured worst 1.8e-5 m (seed_part3 at 1/60) and 1.5e-5 m/s
// (free_fall at 1/240).
double law_tolerance(Scalar s) {
  return s == Scalar::f64 ? 1e-9 : 1e-4;
}

// The largest |engine - law| component of any body at any sample, and where it happened.
struct Worst {
  double dx = 0.0, dv = 0.0;
  std::string where = "nowhere";
};

std::string describe(const Trajectory& run, const Trajectory& law, std::size_t s, std::size_t b) {
  std::ostringstream m;
  m.precision(17);
  const BodyState &e = run.at(s, b), &l = law.at(s, b);
  m << "scene " << run.scene << ", engine " << run.engine << ", body " << run.body_names[b]
    << ", step " << run.recorded[s] << " (h = " << run.h << "): engine x = ("
    << e.position.transpose() << ") v = (" << e.velocity.transpose() << "), law x = ("
    << l.position.transpose() << ") v = (" << l.velocity.transpose() << ")";
  return m.str();
}

Worst worst_vs_law(const Trajectory& run, const Trajectory& law) {
  Worst w;
  for (std::size_t s = 0; s < run.samples(); ++s) {
    for (std::size_t b = 0; b < run.bodies(); ++b) {
      const double dx = (run.at(s, b).position - law.at(s, b).position).cwiseAbs().maxCoeff();
      const double dv = (run.at(s, b).velocity - law.at(s, b).velocity).cwiseAbs().maxCoeff();
      if (std::max(dx, dv) > std::max(w.dx, w.dv)) w.where = describe(run, law, s, b);
      w.dx = std::max(w.dx, dx);
      w.dv = std::max(w.dv, dv);
    }
  }
  return w;
}

// Wraps the real adapter and misreports one thing, as a careless adapter would.
class MisreportingEngine final : public Engine {
 public:
  enum class Fault { wrong_law, per_step_damping };
  MisreportingEngine(std::unique_ptr<Engine> real, Fault fault)
      : real_(std::move(real)), fault_(fault) {}

  EngineInfo info() const override {
    EngineInfo i = real_->info();
    if (fault_ == Fault::wrong_law) i.law = DampingOrder::AfterForces;  // ours' order, not Bullet's
    return i;
  }
  // per_step_damping: d = 1 - exp(-k*h) (the per-step fraction) given to setDamping, which Bullet
  // reads per second: it then decays exp(-k*h*h) per step, as a rate k' = k*h would.
  void load(const Scene& scene, double h) override {
    Scene s = scene;
    if (fault_ == Fault::per_step_damping) s.world.damping_rate *= h;
    real_->load(s, h);
  }
  void set_forces(std::span<const Vec3> f) override { real_->set_forces(f); }
  void step() override { real_->step(); }
  void read(std::span<BodyState> out) const override { real_->read(out); }

 private:
  std::unique_ptr<Engine> real_;
  Fault fault_;
};

}  // namespace

#define REQUIRE_BULLET(engine)                               \
  auto engine = make_engine("bullet");                       \
  if (!engine) {                                             \
    WARN("bullet: " << engine_unavailable_reason("bullet")); \
    return;                                                  \
  }

// Its own law at every step of every shipped scene is checked for every engine by
// tests/adapters/conformance_test.cpp; here only the declaration it is checked against.
TEST_CASE("Bullet declares its damping order for the conformance suite", "[bullet][law]") {
  REQUIRE_BULLET(engine);
  CHECK(engine->info().law == DampingOrder::BeforeForces);
}

TEST_CASE("Bullet reproduces docs/engines.md's 60-step drag figure", "[bullet][law]") {
  REQUIRE_BULLET(engine);
  // 60 steps of h = 1/60, g = -9.8, f = 0.98, x0 = 10, v0 = 0, m = 1 (scenarios/free_fall_drag).
  const Trajectory run = run_scene(*engine, scenario("free_fall_drag"), 1.0 / 60.0);
  REQUIRE(run.recorded.back() == 60);
  const double x = run.final_state(0).position.y();
  if (engine->info().scalar == Scalar::f64) {
    // Measured 6.5182636233228308 exactly (docs/engines.md section 2); 1e-12 leaves room for libm.
    CHECK(x == Approx(6.5182636233228308).epsilon(0).margin(1e-12));
  } else {
    CHECK(x == Approx(6.5182623863220215)
                   .epsilon(0)
                   .margin(1e-6));  // float libs, docs/engines.md section 2
  }
}

TEST_CASE("The own-law check catches a Bullet adapter that misreports its law or its damping",
          "[bullet][law]") {
  REQUIRE_BULLET(probe);
  const Scene scene = scenario("free_fall_drag");
  using Fault = MisreportingEngine::Fault;
  for (const Fault fault : {Fault::wrong_law, Fault::per_step_damping}) {
    const EngineFactory broken = [fault] {
      return std::make_unique<MisreportingEngine>(make_engine("bullet"), fault);
    };
    const CheckResult r = check_own_law(scene, broken, scene.timestep);
    INFO(r.message);
    CHECK_FALSE(r.passed);
    // The message names the body, the step and both values (harness/measure/checks.cpp).
    CHECK_THAT(r.message, Catch::Contains("worst at body 'cube' step") &&
                              Catch::Contains("engine x = (") && Catch::Contains("law x = ("));
  }
  const CheckResult honest = check_own_law(
      scene, [] { return make_engine("bullet"); }, scene.timestep);
  INFO(honest.message);
  CHECK(honest.passed);
}

TEST_CASE("Bullet applies a force for one step only and divides it by the mass", "[bullet]") {
  REQUIRE_BULLET(engine);
  Scene scene = scenario("free_fall");
  scene.world.gravity = Vec3::Zero();
  scene.bodies[0].mass = 3.375;
  engine->load(scene, 1.0 / 60.0);
  const Vec3 force(2.0, -4.0, 0.0);
  engine->set_forces(std::span<const Vec3>(&force, 1));
  engine->step();
  engine->step();  // no set_forces: the force of step 1 must be gone
  BodyState s;
  engine->read(std::span<BodyState>(&s, 1));
  // v = (F*(1/m))*h after step 1, unchanged by step 2. Measured relative error 0 in double,
  // 5e-8 in float.
  const double rel = engine->info().scalar == Scalar::f64 ? 1e-14 : 1e-6;
  CHECK(s.velocity.x() == Approx(2.0 / 3.375 / 60.0).epsilon(rel));
  CHECK(s.velocity.y() == Approx(-4.0 / 3.375 / 60.0).epsilon(rel));
  CHECK(s.position.y() == Approx(10.0 + 2.0 * s.velocity.y() / 60.0).epsilon(rel));
}

TEST_CASE("Bullet reloads cleanly: a second load on one engine replays the first run exactly",
          "[bullet]") {
  REQUIRE_BULLET(engine);
  const Scene wind = scenario("wind"), floor = scenario("drop_on_floor");
  const Trajectory first = run_scene(*engine, wind, 1.0 / 60.0);
  run_scene(*engine, floor, 1.0 / 60.0);  // a contact world in between
  const Trajectory again = run_scene(*engine, wind, 1.0 / 60.0);
  REQUIRE(again.states.size() == first.states.size());
  for (std::size_t i = 0; i < first.states.size(); ++i) {
    CHECK(again.states[i].position == first.states[i].position);
    CHECK(again.states[i].velocity == first.states[i].velocity);
  }
}

TEST_CASE("Bullet reads a static body back at its fixed position with zero velocity", "[bullet]") {
  REQUIRE_BULLET(engine);
  for (const char* name : {"seed_part3", "drop_on_floor"}) {  // contacts off and on
    const Trajectory run = run_scene(*engine, scenario(name), 1.0 / 60.0);
    INFO(name);
    CHECK(run.final_state(0).position == Vec3(0.0, -0.5, 0.0));
    CHECK(run.final_state(0).velocity == Vec3::Zero());
  }
}

TEST_CASE("A cube dropped on a floor lands on time, does not bounce and rests at Bullet's offset",
          "[bullet][landing]") {
  REQUIRE_BULLET(engine);
  const EngineInfo info = engine->info();
  for (const char* name : {"drop_on_floor", "drop_on_floor_undamped"}) {
    const Scene scene = scenario(name);
    const double h = scene.timestep.seconds;
    const std::vector<LandingSetup> setups = landing_setups(scene);
    REQUIRE(setups.size() == 1);
    const LandingSetup& s = setups[0];
    const Trajectory run = run_scene(*engine, scene, h);
    REQUIRE(run.status == RunStatus::ok);
    const LandingObservation o = observe_landing(run, s);
    const std::int64_t law_step = discrete_contact_step(info.law, scene, h, s);
    std::ostringstream figures;
    figures << name << ": first contact step " << o.first_contact_step << " (law " << law_step
            << "), t = " << o.first_contact_time << " s vs analytic " << s.contact_time
            << " s; deepest " << o.deepest << " m, rebound " << o.rebound << " m, rest offset "
            << o.rest_offset << " m, still: |v| " << o.still_speed << " m/s, range "
            << o.still_range << " m";
    INFO(figures.str());
    if (measuring()) WARN(figures.str());
    // Within one step of the engine's own law: measured the same step (114 damped, 84 undamped).
    CHECK(std::abs(o.first_contact_step - law_step) <= 1);
    // Continuous model: t_c = 1.9195 s damped, 1.3924 s undamped. The law itself lands at
    // 1.9 s (-1.17 steps: damping before forces falls 1/f farther than the continuous model, an
    // O(h) drift) and 1.4 s (+0.46 step: the sampling grid); two steps bound both.
    CHECK(std::abs(o.first_contact_time - s.contact_time) <= 2 * h);
    // Measured rebound: the centre never comes back above rest (-2.4e-7, -1.6e-7 m).
    CHECK(o.rebound <= 1e-3);
    // Measured rest offsets -3.2e-7 and -3.5e-7 m.
    CHECK(std::abs(o.rest_offset - info.rest_offset) <= info.rest_tolerance);
    // Measured over the last 2 s: |v| <= 1.6e-4 m/s, range <= 7.6e-5 m (a slow sideways creep).
    CHECK(o.still);
  }
}

TEST_CASE("Bullet's landing never rebounds at any step of the sweep", "[bullet][landing]") {
  REQUIRE_BULLET(engine);
  const EngineInfo info = engine->info();
  for (const char* name : {"drop_on_floor", "drop_on_floor_undamped"}) {
    const Scene scene = scenario(name);
    for (const Timestep& h : scene.timesteps) {
      const LandingSetup s = landing_setups(scene).at(0);
      const LandingObservation o = observe_landing(run_scene(*engine, scene, h.seconds), s);
      std::ostringstream figures;
      figures << name << " at h = " << h.text << ": rebound " << o.rebound << " m, rest offset "
              << o.rest_offset << " m";
      INFO(figures.str());
      if (measuring()) WARN(figures.str());
      // Split impulse for every penetration (threshold 0): measured rebound <= -9e-9 m at every
      // step; with Bullet's default threshold (-0.04 m) shallow first contacts were pushed out by
      // Baumgarte velocity and rebounded 4 mm (1/120) and 2.3 cm (1/240).
      CHECK(o.rebound <= 1e-3);
      // Measured rest offsets from -1.3e-6 m (1/30) to -2e-8 m (1/240).
      CHECK(std::abs(o.rest_offset - info.rest_offset) <= info.rest_tolerance);
    }
  }
}

TEST_CASE("Bullet refuses a damping rate its per-second parameter cannot hold", "[bullet][law]") {
  REQUIRE_BULLET(engine);
  // k = 60 1/s (scenarios/extreme/heavy_drag): d = 1 - exp(-60) = 1 - 8.8e-27 rounds to 1, and
  // Bullet's (1 - d)^h would be 0 instead of exp(-k*h) = 0.61 at 1/120.
  Scene scene = scenario("free_fall");
  scene.world.damping_rate = 60.0;
  CHECK_THAT(engine->cannot_run(scene),
             Catch::Contains("engine limit") && Catch::Contains("to 0.0 digits"));
  const Trajectory run = run_scene(*engine, scene, 1.0 / 120.0);
  CHECK(run.status == RunStatus::engine_error);
  CHECK_THAT(run.failure, Catch::Contains("damping rate k = 60"));
  // Below the limit Bullet runs, but 1 - d carries a relative rounding of up to spacing/exp(-k),
  // and phi = (1 - d)^h h times that: k = 15 1/s holds in double (measured |dx| 3.4e-12 m at
  // 1/120); float needs k = 5 1/s (1 - d = 6.7e-3, rounding 4.5e-6; measured |dx| 4.2e-6 m).
  const bool f64 = engine->info().scalar == Scalar::f64;
  // k = 30 1/s keeps 2.9 digits in double (it drifted 9.2 um from exp(-k*h)): refused, with the
  // reason.
  scene.world.damping_rate = 30.0;
  if (f64)
    CHECK_THAT(engine->cannot_run(scene),
               Catch::Contains("to 2.9 digits") && Catch::Contains("k <= 22.9 1/s"));
  scene.world.damping_rate = f64 ? 15.0 : 5.0;
  CHECK(engine->cannot_run(scene).empty());
  const Trajectory ok = run_scene(*engine, scene, 1.0 / 120.0);
  REQUIRE(ok.status == RunStatus::ok);
  const Worst w = worst_vs_law(ok, predict_discrete(engine->info().law, scene, 1.0 / 120.0));
  INFO(w.where);
  if (measuring())
    WARN("k = " << scene.world.damping_rate << ": |dx| " << w.dx << " |dv| " << w.dv);
  CHECK(w.dx <= law_tolerance(engine->info().scalar));
}
