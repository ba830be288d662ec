// Tests harness/run/isolated_run.cpp: a run in a child process. A test double that aborts,
// segfaults, exits, hangs or fails to allocate at a chosen step stands in for a misbehaving engine;
// every failure must come back as the run's status with the step, and the test process lives on.
#include "harness/run/isolated_run.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <vector>

#include "harness/core/registry.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/fake_engine.hpp"
#include "tests/scene_texts.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

enum class Misdeed { none, abort, segfault, exit7, hang, bad_alloc, say_and_abort, chatter };

// The free-flight double (tests/fake_engine.hpp) with one misdeed at step `at` (or during load when
// at == 0). No scene here has a force, so it moves by x += h*v.
class UnrulyEngine final : public testing::FakeEngine {
 public:
  UnrulyEngine(Misdeed what, std::int64_t at) : FakeEngine("unruly"), what_(what), at_(at) {}

 private:
  void on_load() override {
    if (at_ == 0) misbehave();
  }
  void before_move(std::int64_t step) override {
    if (step == at_ || (what_ == Misdeed::chatter && step > at_)) misbehave();
  }
  void misbehave() {
    switch (what_) {
      case Misdeed::none:
        return;
      case Misdeed::abort:
        std::abort();
      case Misdeed::segfault:
        std::raise(SIGSEGV);
        return;
      case Misdeed::exit7:
        std::_Exit(7);
      case Misdeed::hang:
        for (;;) ::pause();
      case Misdeed::bad_alloc:
        throw std::bad_alloc();
      case Misdeed::say_and_abort:
        std::fputs("engine.cpp:12: solver: Assertion `mass > 0' failed.\n", stderr);
        std::abort();
      case Misdeed::chatter:  // every step from `at` on: one line thrice, another once
        for (int i = 0; i < 3; ++i) std::fputs("solver: LCP internal error\n", stderr);
        std::fputs("step done\x1b[2J\n", stderr);
        std::fflush(stderr);
        return;
    }
  }
  Misdeed what_;
  std::int64_t at_;
};

// 10 steps of 0.1 s; one body in flight.
Scene ten_steps() {
  return parse_scene(testing::scene_head("1.0", "1/10", testing::kEarth) +
                         testing::body_text("a", testing::kZero, "[1.0, 0.0, 0.0]"),
                     "ten_steps.toml");
}

Trajectory isolated(Misdeed what, std::int64_t at, double limit = 0.0) {
  UnrulyEngine e(what, at);
  RunOptions o;
  o.isolation = Isolation::child_process;
  o.time_limit_seconds = limit;
  return run_scene(e, ten_steps(), 0.1, o);
}

// True when this process has no child left to reap (no zombie, nothing running).
bool no_children() {
  return ::waitpid(-1, nullptr, WNOHANG) == -1 && errno == ECHILD;
}

}  // namespace

TEST_CASE("an isolated run returns the same trajectory as an in-process run, bit for bit",
          "[isolation]") {
  const Scene scene = ten_steps();
  for (const std::string& name : known_engine_names()) {
    if (!engine_unavailable_reason(name).empty()) continue;
    INFO(name);
    RunOptions child, here;
    child.isolation = Isolation::child_process;
    here.isolation = Isolation::in_process;
    const Trajectory a = run_scene(*make_engine(name), scene, 0.1, child);
    const Trajectory b = run_scene(*make_engine(name), scene, 0.1, here);
    REQUIRE(a.status == b.status);
    CHECK(a.engine == b.engine);
    CHECK(a.scene == b.scene);
    CHECK(a.steps == b.steps);
    CHECK(a.body_names == b.body_names);
    CHECK(a.recorded == b.recorded);
    REQUIRE(a.states.size() == b.states.size());
    for (std::size_t i = 0; i < a.states.size(); ++i) {
      CHECK(a.states[i].position == b.states[i].position);
      CHECK(a.states[i].velocity == b.states[i].velocity);
    }
    CHECK(a.clamped_steps == b.clamped_steps);
  }
  CHECK(no_children());
}

TEST_CASE("an engine that aborts becomes a crashed run with the signal and the step",
          "[isolation]") {
  const Trajectory t = isolated(Misdeed::abort, 4);
  CHECK(t.status == RunStatus::crashed);
  CHECK(std::string(to_string(t.status)) == "crashed");
  CHECK_THAT(t.failure, StartsWith("SIGABRT at step 4"));
  CHECK(t.failed_step == 4);
  CHECK(t.samples() == 0);
  CHECK(t.engine == "unruly");
  CHECK(t.body_names == std::vector<std::string>{"a"});
  CHECK(no_children());
}

TEST_CASE("an abort while loading the scene is reported as such", "[isolation]") {
  const Trajectory t = isolated(Misdeed::abort, 0);
  CHECK(t.status == RunStatus::crashed);
  CHECK_THAT(t.failure, StartsWith("SIGABRT while loading the scene"));
}

TEST_CASE("a segfault and an unexpected exit are crashes too", "[isolation]") {
  const Trajectory segv = isolated(Misdeed::segfault, 2);
  CHECK(segv.status == RunStatus::crashed);
  CHECK_THAT(segv.failure, StartsWith("SIGSEGV at step 2"));
  const Trajectory exited = isolated(Misdeed::exit7, 9);
  CHECK(exited.status == RunStatus::crashed);
  CHECK_THAT(exited.failure, StartsWith("engine process exited with code 7 at step 9"));
  CHECK(no_children());
}

TEST_CASE("the last line the engine wrote to stderr before dying is quoted in the failure",
          "[isolation]") {
  const Trajectory t = isolated(Misdeed::say_and_abort, 3);
  CHECK(t.failure == "SIGABRT at step 3 (engine.cpp:12: solver: Assertion `mass > 0' failed.)");
}

TEST_CASE("what an engine prints is counted per distinct line, escaped, and kept from the terminal",
          "[isolation]") {
  // Steps 3 to 10 print: 8 steps, 24 and 8 lines.
  const Trajectory t = isolated(Misdeed::chatter, 3);
  REQUIRE(t.status == RunStatus::ok);
  REQUIRE(t.messages.size() == 2);
  CHECK(t.messages[0].text == "solver: LCP internal error");
  CHECK(t.messages[0].count == 24);
  CHECK(t.messages[1].text == "step done\\x1b[2J");
  CHECK(t.messages[1].count == 8);
  CHECK(t.other_lines == 0);
  CHECK(t.messages_text() ==
        "unruly printed 'solver: LCP internal error' 24 times and 'step done\\x1b[2J' 8 times");
  // A quiet engine's isolated run keeps nothing; in process nothing is kept either (the chatter
  // goes where the engine writes it: this test's stderr).
  UnrulyEngine quiet(Misdeed::none, 3);
  CHECK(
      run_scene(quiet, ten_steps(), 0.1, {.isolation = Isolation::child_process}).messages.empty());
  UnrulyEngine chatty(Misdeed::chatter, 3);
  const Trajectory here = run_scene(chatty, ten_steps(), 0.1, {.isolation = Isolation::in_process});
  CHECK(here.status == RunStatus::ok);
  CHECK(here.messages.empty());
}

TEST_CASE("a hung engine is killed at the time limit, reaped, and reported with its step",
          "[isolation]") {
  const auto start = std::chrono::steady_clock::now();
  const Trajectory t = isolated(Misdeed::hang, 6, 0.3);
  const double took =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(t.status == RunStatus::timed_out);
  CHECK(t.failure == "no result within the limit of 0.3 s; killed at step 6");
  CHECK(t.failed_step == 6);
  CHECK(took < 5.0);  // measured 0.30 s
  CHECK(no_children());
}

TEST_CASE(
    "an allocation failure is its own status, in a child and in process, and invents no state",
    "[isolation]") {
  const Trajectory child = isolated(Misdeed::bad_alloc, 5);
  UnrulyEngine e(Misdeed::bad_alloc, 5);
  const Trajectory here = run_scene(e, ten_steps(), 0.1, {.isolation = Isolation::in_process});
  for (const Trajectory* t : {&child, &here}) {
    CHECK(t->status == RunStatus::out_of_memory);
    CHECK(std::string(to_string(t->status)) == "out of memory");
    CHECK(t->failure == "allocation failed at step 5");
    // Steps 0..4 were recorded; the last one is the true state after step 4 (x = 0.4), not zeros.
    REQUIRE(t->samples() == 5);
    CHECK(t->recorded.back() == 4);
    CHECK(t->final_state(0).position.x() == Approx(0.4));
  }
}

TEST_CASE("the process default decides where a run without an explicit choice goes",
          "[isolation]") {
  REQUIRE(default_isolation() == Isolation::in_process);
  set_default_isolation(Isolation::child_process);
  UnrulyEngine e(Misdeed::abort, 2);
  const Trajectory t = run_scene(e, ten_steps(), 0.1);  // would end this test binary in process
  set_default_isolation(Isolation::in_process);
  CHECK(t.status == RunStatus::crashed);
  CHECK(runs_isolated({.isolation = Isolation::child_process}));
  CHECK_FALSE(runs_isolated({}));
}

// The cost of isolation, for docs/runs.md (hidden: run with `dropcheck_tests "[.isolation-cost]"`).
TEST_CASE("isolation cost per run: fork, pipe transfer and reaping", "[.isolation-cost]") {
  const Scene scene = load_scene(std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/free_fall.toml");
  for (const Scene& s : {ten_steps(), scene}) {
    double secs[2] = {0, 0};
    for (int mode = 0; mode < 2; ++mode) {
      const RunOptions o{.isolation = mode ? Isolation::child_process : Isolation::in_process};
      const auto start = std::chrono::steady_clock::now();
      for (int i = 0; i < 200; ++i) run_scene(*make_engine("ours-f64"), s, s.timestep.seconds, o);
      secs[mode] =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / 200;
    }
    std::printf("%s (%lld steps): in process %.1f us, isolated %.1f us, cost %.1f us per run\n",
                s.name.c_str(), static_cast<long long>(step_count(s, s.timestep.seconds)),
                secs[0] * 1e6, secs[1] * 1e6, (secs[1] - secs[0]) * 1e6);
  }
}
