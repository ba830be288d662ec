// Tests harness/run/runner.cpp: the one run loop. A scripted test double stands in for an engine
// so that failures (NaN, EngineError) and the force hand-over can be placed at chosen steps.
#include "harness/run/runner.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <tuple>
#include <vector>

#include "harness/core/registry.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/fake_engine.hpp"
#include "tests/scene_texts.hpp"

using Catch::Matchers::Contains;
using dropcheck::testing::body_text;
using dropcheck::testing::kEarth;
using dropcheck::testing::kZero;
using dropcheck::testing::scene_head;

namespace {

// The free-flight double (tests/fake_engine.hpp), scripted: it can turn the last body's velocity
// into NaN on one step, throw on one step or on load, clamp on steps, and it logs the forces each
// set_forces call saw.
class ScriptedEngine final : public dropcheck::testing::FakeEngine {
 public:
  std::int64_t nan_at = -1, throw_at = -1;
  double bad_value = std::numeric_limits<double>::quiet_NaN();  // what nan_at writes
  bool throw_on_load = false;
  std::vector<std::int64_t> clamp_at;
  std::vector<std::vector<dropcheck::Vec3>> forces_seen;

  ScriptedEngine() : FakeEngine("scripted") {}
  bool speed_clamped() const override {
    return std::find(clamp_at.begin(), clamp_at.end(), steps_taken()) != clamp_at.end();
  }

 private:
  void on_load() override {
    if (throw_on_load) throw dropcheck::EngineError("cannot build the world");
  }
  void on_forces(const std::vector<dropcheck::Vec3>& f) override { forces_seen.push_back(f); }
  void before_move(std::int64_t step) override {
    if (step == throw_at) throw dropcheck::EngineError("solver exploded");
  }
  void after_move(std::int64_t step) override {
    if (step == nan_at) states_.back().velocity.y() = bad_value;
  }
};

// 10 steps of 0.1 s; two bodies, a spring on "b" so the forces depend on the state.
dropcheck::Scene ten_steps_with_a_spring() {
  return dropcheck::parse_scene(scene_head("1.0", "1/10", kZero) +
                                    body_text("a", kZero, "[1.0, 0.0, 0.0]") +
                                    body_text("b", "[0.0, 2.0, 0.0]") + R"(
[[force]]
bodies = ["b"]
spring = { anchor = [0.0, 0.0, 0.0], stiffness = 3.0, damping = 0.5 }
)",
                                "ten_steps.toml");
}

std::vector<std::int64_t> steps_of(const dropcheck::Trajectory& t) {
  return t.recorded;
}

}  // namespace

TEST_CASE("a run that completes records every step, step 0 being the initial state", "[runner]") {
  ScriptedEngine e;
  const dropcheck::Scene s = ten_steps_with_a_spring();
  const dropcheck::Trajectory t = dropcheck::run_scene(e, s, 0.1);
  CHECK(t.status == dropcheck::RunStatus::ok);
  CHECK(t.engine == "scripted");
  CHECK(t.steps == 10);
  CHECK(t.body_names == std::vector<std::string>{"a", "b"});
  CHECK(steps_of(t) == std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10});
  CHECK(t.at(0, 1).position == dropcheck::Vec3(0.0, 2.0, 0.0));
  CHECK(t.at(10, 0).position.x() ==
        Approx(1.0).epsilon(1e-15));  // x = 10 * 0.1 * 1; measured 1.1e-16
  CHECK(t.failed_step == -1);
}

TEST_CASE("a NaN at step k ends the run as non_finite at k and keeps the samples before it",
          "[runner]") {
  ScriptedEngine e;
  e.nan_at = 4;
  const dropcheck::Trajectory t = dropcheck::run_scene(e, ten_steps_with_a_spring(), 0.1);
  CHECK(t.status == dropcheck::RunStatus::non_finite);
  CHECK(t.failed_step == 4);
  CHECK(steps_of(t) == std::vector<std::int64_t>{0, 1, 2, 3});
  CHECK(t.states.size() == 4 * 2);
  CHECK_THAT(t.failure, Contains("'b'") && Contains("step 4"));
  CHECK(std::isfinite(t.final_state(1).velocity.y()));
}

TEST_CASE("a NaN on a step that is not sampled ends the run at that step", "[runner]") {
  ScriptedEngine e;
  e.nan_at = 6;
  const dropcheck::Trajectory t =
      dropcheck::run_scene(e, ten_steps_with_a_spring(), 0.1, {.record_every = 4});
  CHECK(t.status == dropcheck::RunStatus::non_finite);
  CHECK(t.failed_step == 6);
  CHECK(steps_of(t) == std::vector<std::int64_t>{0, 4});
  CHECK(t.states.size() == 2 * 2);
  CHECK_THAT(t.failure, Contains("'b'") && Contains("step 6"));
}

TEST_CASE("an infinite state counts as non_finite like a NaN, on a sampled step too", "[runner]") {
  for (const double bad :
       {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
    ScriptedEngine e;
    e.nan_at = 8;
    e.bad_value = bad;
    const dropcheck::Trajectory t =
        dropcheck::run_scene(e, ten_steps_with_a_spring(), 0.1, {.record_every = 4});
    CHECK(t.status == dropcheck::RunStatus::non_finite);
    CHECK(t.failed_step == 8);
    CHECK(steps_of(t) == std::vector<std::int64_t>{0, 4});  // step 8 is not kept
  }
  ScriptedEngine big;  // the largest finite double is finite
  big.nan_at = 8;
  big.bad_value = std::numeric_limits<double>::max();
  CHECK(dropcheck::run_scene(big, ten_steps_with_a_spring(), 0.1).status ==
        dropcheck::RunStatus::ok);
}

TEST_CASE("a run's samples are sized once, to exactly the samples it keeps", "[runner]") {
  for (const std::int64_t every : {1, 3, 4, 5, 10, 100}) {
    ScriptedEngine e;
    const dropcheck::Trajectory t =
        dropcheck::run_scene(e, ten_steps_with_a_spring(), 0.1, {.record_every = every});
    INFO("record_every " << every);
    CHECK(t.recorded.capacity() == t.recorded.size());
    CHECK(t.states.capacity() == t.states.size());
    CHECK(t.states.size() == t.samples() * 2);
  }
}

TEST_CASE("sampling every few steps hands the engine the same forces as sampling every step",
          "[runner]") {
  ScriptedEngine every_step, every_third;
  const dropcheck::Trajectory a = dropcheck::run_scene(every_step, ten_steps_with_a_spring(), 0.1);
  const dropcheck::Trajectory b =
      dropcheck::run_scene(every_third, ten_steps_with_a_spring(), 0.1, {.record_every = 3});
  CHECK(every_third.forces_seen == every_step.forces_seen);  // exact: same doubles
  CHECK(b.final_state(1).position == a.final_state(1).position);
}

TEST_CASE("constant forces reach the engine on every step, summed per body", "[runner]") {
  const dropcheck::Scene s =
      dropcheck::parse_scene(scene_head("1.0", "1/10", kZero) + body_text("a", kZero) +
                                 body_text("b", "[0.0, 2.0, 0.0]") + R"(
[[force]]
bodies = ["a"]
constant = [1.0, 2.0, 0.0]
[[force]]
bodies = ["a", "b"]
constant = [0.5, 0.0, -1.0]
)",
                             "constant.toml");
  ScriptedEngine e;
  const dropcheck::Trajectory t = dropcheck::run_scene(e, s, 0.1);
  REQUIRE(t.status == dropcheck::RunStatus::ok);
  REQUIRE(e.forces_seen.size() == 10);
  for (const std::vector<dropcheck::Vec3>& f : e.forces_seen) {
    CHECK(f[0] == dropcheck::Vec3(1.5, 2.0, -1.0));
    CHECK(f[1] == dropcheck::Vec3(0.5, 0.0, -1.0));
  }
}

TEST_CASE("an EngineError at step k ends the run as engine_error with its message", "[runner]") {
  ScriptedEngine e;
  e.throw_at = 7;
  const dropcheck::Trajectory t = dropcheck::run_scene(e, ten_steps_with_a_spring(), 0.1);
  CHECK(t.status == dropcheck::RunStatus::engine_error);
  CHECK(t.failure == "solver exploded");
  CHECK(t.failed_step == 7);
  CHECK(steps_of(t) == std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6});
}

TEST_CASE("an EngineError on load is engine_error at step 0 with no samples", "[runner]") {
  ScriptedEngine e;
  e.throw_on_load = true;
  const dropcheck::Trajectory t = dropcheck::run_scene(e, ten_steps_with_a_spring(), 0.1);
  CHECK(t.status == dropcheck::RunStatus::engine_error);
  CHECK(t.failure == "cannot build the world");
  CHECK(t.failed_step == 0);
  CHECK(t.samples() == 0);
}

TEST_CASE("record_every keeps step 0, every Nth step and the last step", "[runner]") {
  ScriptedEngine e;
  CHECK(steps_of(dropcheck::run_scene(e, ten_steps_with_a_spring(), 0.1, {.record_every = 4})) ==
        std::vector<std::int64_t>{0, 4, 8, 10});
  ScriptedEngine e2;
  CHECK(steps_of(dropcheck::run_scene(e2, ten_steps_with_a_spring(), 0.1, {.record_every = 5})) ==
        std::vector<std::int64_t>{0, 5, 10});  // the last step is not recorded twice
  ScriptedEngine e3;
  CHECK(steps_of(dropcheck::run_scene(e3, ten_steps_with_a_spring(), 0.1, {.record_every = 100})) ==
        std::vector<std::int64_t>{0, 10});
  ScriptedEngine e4;
  CHECK(dropcheck::run_scene(e4, ten_steps_with_a_spring(), 0.1, {.record_every = 0}).samples() ==
        11);  // < 1 means 1
}

TEST_CASE("speed clamps are counted with the first clamped step", "[runner]") {
  ScriptedEngine e;
  e.clamp_at = {3, 8};
  const dropcheck::Trajectory t = dropcheck::run_scene(e, ten_steps_with_a_spring(), 0.1);
  CHECK(t.clamped_steps == 2);
  CHECK(t.first_clamped_step == 3);
  CHECK(t.status == dropcheck::RunStatus::ok);  // a clamp is reported, not a failure
}

TEST_CASE("the force handed to step n is the spring force of the state after step n-1",
          "[runner]") {
  ScriptedEngine e;
  const dropcheck::Trajectory t = dropcheck::run_scene(e, ten_steps_with_a_spring(), 0.1);
  REQUIRE(e.forces_seen.size() == 10);
  for (std::size_t n = 0; n < 10; ++n) {
    // F = -stiffness*d - damping*v with d = x - anchor (rest length 0), from sample n.
    const dropcheck::BodyState& b = t.at(n, 1);
    const dropcheck::Vec3 expected = -3.0 * b.position - 0.5 * b.velocity;
    INFO("step " << n + 1);
    CHECK(e.forces_seen[n][1] == expected);  // same operations on the same doubles: exact
    CHECK(e.forces_seen[n][0] == dropcheck::Vec3::Zero());  // "a" has no force
  }
}

TEST_CASE("zero constant forces are handed to the engine on the first step only", "[runner]") {
  const dropcheck::Scene s = dropcheck::parse_scene(
      scene_head("1.0", "1/10", kZero) + body_text("a", kZero, "[1.0, 0.0, 0.0]"), "free.toml");
  ScriptedEngine e;
  const dropcheck::Trajectory t = dropcheck::run_scene(e, s, 0.1);
  REQUIRE(t.status == dropcheck::RunStatus::ok);
  REQUIRE(e.forces_seen.size() == 1);  // step 1; the other 9 steps would hand the same zeros
  CHECK(e.forces_seen[0] == std::vector<dropcheck::Vec3>{dropcheck::Vec3::Zero()});
  CHECK(t.final_state(0).position.x() == Approx(1.0).epsilon(1e-15));
}

TEST_CASE("every engine runs bit-identically whether or not zero forces are handed every step",
          "[runner]") {
  // A planar free flight with drag and a static floor far below (Box2D runs it too).
  const dropcheck::Scene s =
      dropcheck::parse_scene(scene_head("1.0", "", kEarth, "linear_damping = 0.7\n") +
                                 body_text("floor", "[0.0, -50.0, 0.0]", "",
                                           "static = true\nhalf_extents = [5.0, 0.5, 5.0]\n") +
                                 body_text("cube", "[0.0, 10.0, 0.0]", "[1.0, 2.0, 0.0]"),
                             "free_drag.toml");
  const double h = 1.0 / 60;
  for (const std::string& name : dropcheck::available_engine_names()) {
    if (name.rfind("exec:", 0) == 0) continue;
    auto engine = dropcheck::make_engine(name);
    if (!engine || !engine->cannot_run(s).empty()) continue;
    const dropcheck::Trajectory run = dropcheck::run_scene(*engine, s, h);
    REQUIRE(run.status == dropcheck::RunStatus::ok);
    // The loop run_scene had before: zeros handed over on every step.
    auto fresh = dropcheck::make_engine(name);
    fresh->load(s, h);
    const std::vector<dropcheck::Vec3> zeros(s.bodies.size(), dropcheck::Vec3::Zero());
    std::vector<dropcheck::BodyState> now(s.bodies.size());
    for (std::int64_t n = 1; n <= run.steps; ++n) {
      fresh->set_forces(zeros);
      fresh->step();
    }
    fresh->read(now);
    INFO(name);
    CHECK(now[1].position == run.final_state(1).position);  // exact: the same operations
    CHECK(now[1].velocity == run.final_state(1).velocity);
  }
}

TEST_CASE("a spring scene on ours-f64 follows its AfterForces law to 1e-12", "[runner][ours]") {
  // Forces from the state at the start of each step in both: the runner hands the engine
  // F(x_n, v_n); predict_discrete evaluates the same F on its own state (long double iteration).
  const dropcheck::Scene s = dropcheck::parse_scene(
      scene_head("2.0", "", kEarth, "linear_drag = 0.98\n") +
          body_text("bob", "[0.5, 4.0, 0.0]", "[0.0, 1.0, 0.0]", "mass = 2.0\n") + R"(
[[force]]
spring = { anchor = [0.0, 5.0, 0.0], stiffness = 400.0, damping = 1.5, rest_length = 0.25 }
)",
      "spring.toml");
  auto engine = dropcheck::make_engine("ours-f64");
  REQUIRE(engine);
  const dropcheck::Trajectory run = dropcheck::run_scene(*engine, s, s.timestep.seconds);
  const dropcheck::Trajectory law =
      dropcheck::predict_discrete(dropcheck::DampingOrder::AfterForces, s, s.timestep.seconds);
  REQUIRE(run.status == dropcheck::RunStatus::ok);
  REQUIRE(run.samples() == law.samples());
  double dx = 0.0, dv = 0.0;
  for (std::size_t i = 0; i < run.samples(); ++i) {
    dx = std::max(dx, (run.at(i, 0).position - law.at(i, 0).position).cwiseAbs().maxCoeff());
    dv = std::max(dv, (run.at(i, 0).velocity - law.at(i, 0).velocity).cwiseAbs().maxCoeff());
  }
  CHECK(dx < 1e-12);  // measured 3.8e-15
  CHECK(dv < 1e-12);  // measured 4.5e-14
  // The spring really matters: the bob is far from a free fall after 2 s.
  CHECK(std::abs(run.final_state(0).position.y() - 5.0) < 1.0);
}

TEST_CASE("an engine whose read_append gives the wrong number of states ends as engine_error",
          "[runner]") {
  // ours with a read_append that drops the last body: the runner's count check, not a short row.
  class ShortAppend final : public dropcheck::Engine {
   public:
    dropcheck::EngineInfo info() const override { return inner_->info(); }
    void load(const dropcheck::Scene& s, double h) override { inner_->load(s, h); }
    void set_forces(std::span<const dropcheck::Vec3> f) override { inner_->set_forces(f); }
    void step() override { inner_->step(); }
    void read(std::span<dropcheck::BodyState> out) const override { inner_->read(out); }
    bool read_append(std::size_t bodies, dropcheck::StateBuffer& out,
                     dropcheck::StateUse use) const override {
      const bool finite = inner_->read_append(bodies, out, use);
      out.pop_back();
      return finite;
    }

   private:
    std::unique_ptr<dropcheck::Engine> inner_ = dropcheck::make_engine("ours");
  };
  ShortAppend e;
  dropcheck::Scene s = ten_steps_with_a_spring();
  s.forces.clear();  // ours runs free bodies
  const dropcheck::Trajectory t = dropcheck::run_scene(e, s, 0.1, {.record_every = 4});
  CHECK(t.status == dropcheck::RunStatus::engine_error);
  CHECK(t.failed_step == 0);
  CHECK_THAT(t.failure, Contains("1 states for 2 bodies"));
  CHECK(t.samples() == 0);
  CHECK(t.states.empty());
}

TEST_CASE("ours and ours-f64 end a run whose state overflows as non_finite, kept step or not",
          "[runner]") {
  // h = 0.1, no damping, g below each scalar's range (ours refuses a scene value beyond FLT_MAX):
  // v = -n * g * h passes the largest number on step 12 in f32 (g = 3e38: 12 * 3e37 > 3.4e38) and
  // on step 18 in f64 (g = 1e308: 18 * 1e307 > 1.8e308). With record_every = 1 the step is kept,
  // with 5 it is not: both read paths (StateUse::kept and the scratch) are checked.
  dropcheck::Scene s = ten_steps_with_a_spring();
  s.forces.clear();  // ours runs free bodies
  s.duration = 3.0;  // 30 steps
  s.world.damping_rate = 0.0;
  for (const auto& [engine, g, step] : {std::tuple{"ours", 3e38, 12}, {"ours-f64", 1e308, 18}}) {
    s.world.gravity = {0.0, -g, 0.0};
    for (const std::int64_t every : {1, 5}) {
      const std::unique_ptr<dropcheck::Engine> e = dropcheck::make_engine(engine);
      const dropcheck::Trajectory t = dropcheck::run_scene(*e, s, 0.1, {.record_every = every});
      INFO(engine << ", every " << every);
      CHECK(t.status == dropcheck::RunStatus::non_finite);
      CHECK(t.failed_step == step);
      CHECK(t.states.size() == t.samples() * t.bodies());
      CHECK(dropcheck::all_finite(t.states));
    }
  }
}

TEST_CASE("ours and ours-f64 stream the kept states of a large run bit for bit, overflow included",
          "[runner]") {
  // 100 free bodies (4800 B per step) for 3600 steps (17.3 MB kept at record_every = 1) pass both
  // thresholds of kept_states_use (4 KiB per step, 16 MiB per run): streamed stores. Every second
  // step (8.6 MB) stays below them: normal stores. The kept states must be the same bits.
  dropcheck::Scene s = ten_steps_with_a_spring();
  s.forces.clear();
  s.duration = 36.0;  // 3600 steps at h = 0.01
  s.world.damping_rate = 0.5;
  const dropcheck::Body free_body = s.bodies[0];
  s.bodies.clear();
  for (int i = 0; i < 100; ++i) {
    s.bodies.push_back(free_body);
    s.bodies.back().name = "b" + std::to_string(i);
    s.bodies.back().position = {2.0 * i, 10.0 + i, 0.0};
    s.bodies.back().velocity = {1.0, 0.1 * i, -0.5};
  }
  for (const char* engine : {"ours", "ours-f64"}) {
    INFO(engine);
    const auto run = [&](std::int64_t every) {
      const std::unique_ptr<dropcheck::Engine> e = dropcheck::make_engine(engine);
      return dropcheck::run_scene(*e, s, 0.01, {.record_every = every});
    };
    const dropcheck::Trajectory all = run(1), half = run(2);
    REQUIRE(all.status == dropcheck::RunStatus::ok);
    REQUIRE(all.samples() == 3601);
    REQUIRE(half.samples() == 1801);
    bool same = true;
    for (std::size_t k = 0; k < half.samples(); ++k)
      for (std::size_t b = 0; b < 100; ++b) {
        const dropcheck::BodyState &x = all.at(2 * k, b), &y = half.at(k, b);
        same = same && std::memcmp(&x, &y, sizeof x) == 0;
      }
    CHECK(same);
  }
  // The same large run overflowing part way: streamed kept states are checked as they are written.
  s.world.damping_rate = 0.0;
  for (const auto& [engine, g] : {std::pair{"ours", 3e38}, {"ours-f64", 1e308}}) {
    s.world.gravity = {0.0, -g, 0.0};
    const std::unique_ptr<dropcheck::Engine> e = dropcheck::make_engine(engine);
    const dropcheck::Trajectory t = dropcheck::run_scene(*e, s, 0.01, {.record_every = 1});
    INFO(engine);
    CHECK(t.status == dropcheck::RunStatus::non_finite);
    CHECK(t.failed_step > 100);  // v = -n g h passes the largest number near n = 114 / 180
    CHECK(t.failed_step < 200);
    CHECK(t.states.size() == t.samples() * t.bodies());
    CHECK(dropcheck::all_finite(t.states));
  }
}
