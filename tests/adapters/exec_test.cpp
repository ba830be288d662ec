// Tests adapters/exec.cpp: external engines through the protocol of docs/protocol.md. The examples
// match the compiled ours bit for bit and pass `check`; the wrong example fails it; every kind of
// bad engine (tests/adapters/bad_engine.py) is a recorded result naming the step, never a hang or a
// crash of dropcheck, and no child process outlives its engine.
#include "adapters/exec.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/cli/cli.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/checks.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

const std::string kExecSource = DROPCHECK_SOURCE_DIR;
const std::string kPython = kExecSource + "/examples/python/seed_engine.toml";
const std::string kWrong = kExecSource + "/examples/python/wrong_order.toml";
const std::string kC = std::string("exec:") + DROPCHECK_SEED_ENGINE_C;
const std::string kBad = kExecSource + "/tests/adapters/bad_engine.py";

Scene exec_scene(const std::string& name) {
  return load_scene(kExecSource + "/scenarios/" + name + ".toml");
}

Trajectory run_exec(const std::string& engine, const Scene& s) {
  auto e = make_engine(engine);
  REQUIRE(e);
  return run_scene(*e, s, s.timestep.seconds);
}

// True when this process has no child left, running or zombie.
bool exec_no_children() {
  int status = 0;
  return ::waitpid(-1, &status, WNOHANG) == -1 && errno == ECHILD;
}

void require_exec_same_bits(const Trajectory& a, const Trajectory& b) {
  REQUIRE(a.status == RunStatus::ok);
  REQUIRE(a.samples() == b.samples());
  for (std::size_t i = 0; i < a.states.size(); ++i) {
    INFO("state " << i);
    REQUIRE(a.states[i].position == b.states[i].position);
    REQUIRE(a.states[i].velocity == b.states[i].velocity);
  }
}

// A bad engine in MODE that misbehaves at step `at`, with a short timeout.
Trajectory run_bad(const std::string& mode, int at, double timeout_s = 2.0) {
  ExecSpec spec;
  spec.command = {"python3", kBad, mode, std::to_string(at)};
  spec.timeout_s = timeout_s;
  const Scene s = exec_scene("wind");
  Trajectory t;
  {
    auto e = make_exec_engine(spec);
    t = run_scene(*e, s, s.timestep.seconds);
  }
  return t;
}

// The InputError message of parse_exec_spec(spec), or "no error".
std::string exec_error_of(const std::string& spec) {
  try {
    parse_exec_spec(spec);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string write_file(const std::string& name, const std::string& text) {
  const fs::path p =
      fs::temp_directory_path() / ("dropcheck_exec_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(p) << text;
  return p.string();
}

}  // namespace

TEST_CASE("The Python seed engine follows ours-f64 bit for bit over the protocol", "[exec]") {
  for (const char* name : {"wind", "throw_up", "seed_part3"}) {
    INFO(name);
    const Scene s = exec_scene(name);
    require_exec_same_bits(run_exec(kPython, s), run_exec("ours-f64", s));
  }
  CHECK(make_engine(kPython)->info().name == "seed-python");
  CHECK(make_engine(kPython)->info().scalar == Scalar::f64);
  CHECK(exec_no_children());
}

TEST_CASE("The C seed engine in float follows ours (f32) bit for bit over the protocol", "[exec]") {
  for (const char* name : {"wind", "throw_up", "seed_part3"}) {
    INFO(name);
    const Scene s = exec_scene(name);
    require_exec_same_bits(run_exec(kC, s), run_exec("ours", s));
  }
  const EngineInfo info = make_engine(kC)->info();
  CHECK(info.name == "seed-c");
  CHECK(info.scalar == Scalar::f32);
  CHECK(info.law == Law{DampingOrder::AfterForces});
}

TEST_CASE("check passes the example engines and fails the wrong-order one on its own law",
          "[exec]") {
  const Scene s = exec_scene("throw_up");
  const EngineFactory ref = [] { return make_engine("ours-f64"); };
  for (const std::string& engine : {kPython, kC}) {
    for (const CheckResult& r : check_scene(
             s, [engine] { return make_engine(engine); }, ref)) {
      INFO(engine << ": " << r.check << ": " << r.message);
      CHECK(r.passed);
    }
  }
  const CheckResult wrong = check_own_law(
      s, [] { return make_engine(kWrong); }, s.timestep);
  CHECK_FALSE(wrong.passed);
  CHECK(wrong.engine == "wrong-order");
}

TEST_CASE("run and check accept an external engine on the command line", "[exec][cli]") {
  std::ostringstream out, err;
  REQUIRE(cli_main({"run", kExecSource + "/scenarios/wind.toml", "--engine", kPython}, out, err) ==
          kExitOk);
  CHECK_THAT(out.str(), Contains("seed-python small") && Contains("120") && Contains("ok"));
  out.str("");
  REQUIRE(cli_main({"check", kExecSource + "/scenarios/wind.toml", "--engine", kC}, out, err) ==
          kExitOk);
  CHECK_THAT(out.str(),
             Contains("PASS  wind  seed-c  own law at h = 1/60") && Contains("0 failed"));
  out.str("");
  CHECK(cli_main({"check", kExecSource + "/scenarios/wind.toml", "--engine", kWrong}, out, err) ==
        kExitCheckFailed);
  CHECK_THAT(out.str(), Contains("FAIL  wind  wrong-order  own law"));
}

TEST_CASE("A crashing engine is a result naming the signal and the step", "[exec]") {
  const Trajectory t = run_bad("crash", 3);
  CHECK(t.status == RunStatus::crashed);  // its process died, as a built-in engine's would
  CHECK(t.failed_step == 3);
  CHECK_THAT(t.failure, Contains("at step 3: the engine crashed: SIGSEGV"));
  CHECK(t.samples() == 3);  // steps 0, 1, 2 recorded
  CHECK(exec_no_children());
}

TEST_CASE("A hanging engine times out at its step and is killed", "[exec]") {
  const auto start = std::chrono::steady_clock::now();
  const Trajectory t = run_bad("hang", 2, 1.5);  // 1.5 s: also bounds python's start (handshake)
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(t.status == RunStatus::engine_error);
  CHECK(t.failed_step == 2);
  CHECK_THAT(t.failure, Contains("at step 2: no answer within 1.5 s (timeout; engine killed)"));
  CHECK(seconds < 5.0);  // measured 1.6 s (1.5 s timeout + python start), never the 60 s sleep
  CHECK(exec_no_children());
}

TEST_CASE("Garbage, a wrong body count, an error line and an early exit are results", "[exec]") {
  const Trajectory garbage = run_bad("garbage", 4);
  CHECK(garbage.failed_step == 4);
  CHECK_THAT(garbage.failure,
             Contains("at step 4: garbage from the engine: expected 'state 4' and 12 "
                      "numbers, got 'hello world'"));
  const Trajectory bodies = run_bad("bodies", 5);
  CHECK(bodies.failed_step == 5);
  CHECK_THAT(bodies.failure,
             Contains("at step 5: the engine answered 6 numbers (1 bodies), the scene has "
                      "2 bodies (12 numbers)"));
  const Trajectory error = run_bad("error", 6);
  CHECK(error.failed_step == 6);
  CHECK_THAT(error.failure, Contains("at step 6: the engine reported an error: out of memory"));
  const Trajectory exit = run_bad("exit", 7);
  CHECK(exit.failed_step == 7);
  CHECK_THAT(exit.failure, Contains("at step 7: the engine exited early (exited with status 0)"));
  for (const Trajectory* t : {&garbage, &bodies, &error})
    CHECK(t->status == RunStatus::engine_error);
  CHECK(exit.status == RunStatus::crashed);  // its process went away
  CHECK(exec_no_children());
}

TEST_CASE("An engine answering NaN is recorded as a non-finite state at that step", "[exec]") {
  const Trajectory t = run_bad("nan", 8);
  CHECK(t.status == RunStatus::non_finite);
  CHECK(t.failed_step == 8);
  CHECK_THAT(t.failure, Contains("NaN/Inf state at step 8"));
}

TEST_CASE("A wrong handshake, a silent engine and a missing program fail at start", "[exec]") {
  const Trajectory version = run_bad("handshake", 0);
  CHECK(version.status == RunStatus::engine_error);
  CHECK_THAT(version.failure,
             Contains("at start: the engine speaks protocol '2'; dropcheck speaks 1"));
  const Trajectory silent = run_bad("silent", 0, 1.0);
  CHECK_THAT(silent.failure, Contains("at start: no answer within 1 s"));
  ExecSpec missing;
  missing.command = {"/nonexistent/engine"};
  auto e = make_exec_engine(missing);
  CHECK(e->info().name == "engine");
  const Scene s = exec_scene("wind");
  const Trajectory t = run_scene(*e, s, s.timestep.seconds);
  CHECK(t.status == RunStatus::engine_error);
  CHECK_THAT(t.failure, Contains("at start: cannot start '/nonexistent/engine'"));
  e.reset();
  CHECK(exec_no_children());
}

TEST_CASE("The handshake declares continuous collision with the capability continuous-collision",
          "[exec]") {
  // An engine that only shakes hands and waits for quit: its info and, for a refused handshake,
  // the failure the first run reports (an accepted one would wait for a state that never comes).
  struct Seen {
    EngineInfo info;
    std::string failure;
  };
  const auto shake = [](const std::string& tag, const std::string& capabilities, bool run) {
    const std::string script =
        write_file("caps_" + tag + ".py",
                   "import sys\n"
                   "for l in ['dropcheck-engine 1', 'name caps', 'version 0', 'scalar f64',\n"
                   "          'law after-forces', '" +
                       capabilities +
                       "', 'ready']:\n"
                       "    print(l, flush=True)\n"
                       "for line in sys.stdin:\n"
                       "    if line.strip() == 'quit':\n"
                       "        break\n");
    ExecSpec spec;
    spec.command = {"python3", script};
    spec.timeout_s = 2.0;
    Seen seen;
    {
      auto e = make_exec_engine(spec);
      seen.info = e->info();
      const Scene s = exec_scene("wind");
      if (run) seen.failure = run_scene(*e, s, s.timestep.seconds).failure;
    }
    fs::remove(script);
    return seen;
  };
  const Seen ccd = shake("ccd", "capabilities contacts continuous-collision", false);
  CHECK(ccd.info.capabilities.contacts);
  CHECK(ccd.info.continuous_collision);
  const Seen plain = shake("plain", "capabilities contacts", false);
  CHECK_FALSE(plain.info.continuous_collision);  // not declared: overlap tested at step ends only
  const Seen bad = shake("bad", "capabilities contacts ccd", true);
  CHECK_THAT(bad.failure,
             Contains("at start") && Contains("capabilities 'contacts', 'planar-only', "
                                              "'continuous-collision', 'rotation', 'rotation-z', "
                                              "'friction', 'restitution' or 'spheres'"));
  CHECK(exec_no_children());
}

TEST_CASE("Engine files and exec: paths are validated as input", "[exec]") {
  CHECK(is_exec_spec("exec:./x"));
  CHECK(is_exec_spec("a/b.toml"));
  CHECK_FALSE(is_exec_spec("ours"));
  CHECK_THAT(exec_error_of("/nonexistent/e.toml"),
             Contains("/nonexistent/e.toml: no such engine file"));
  CHECK_THAT(exec_error_of("exec:/nonexistent"),
             Contains("'/nonexistent': No such file or directory"));
  CHECK_THAT(exec_error_of(write_file("a.toml", "name = \"x\"\n")), Contains("command: missing"));
  CHECK_THAT(exec_error_of(write_file("b.toml", "command = [\"x\"]\nspeed = 3\n")),
             Contains(":2: speed: unknown key (known: name, command, timeout)"));
  CHECK_THAT(exec_error_of(write_file("c.toml", "command = [\"x\"]\ntimeout = -1\n")),
             Contains("timeout: must be a number of seconds in (0, 3600]"));
  CHECK_THAT(exec_error_of(write_file("d.toml", "command = []\n")),
             Contains("command: must be a non-empty array"));
  CHECK_THAT(exec_error_of(write_file("e.toml", "name = \"ours\"\ncommand = [\"x\"]\n")),
             Contains("'ours' is the name of a built-in engine"));
  CHECK_THAT(exec_error_of(write_file("f.toml", "name = \"a b\"\ncommand = [\"x\"]\n")),
             Contains("not a valid engine name"));
  const ExecSpec ok =
      parse_exec_spec(write_file("g.toml", "command = [\"python3\", \"e.py\"]\ntimeout = 0.5\n"));
  CHECK(ok.command == std::vector<std::string>{"python3", "e.py"});
  CHECK(ok.timeout_s == 0.5);
  CHECK(ok.cwd == fs::temp_directory_path().string());
  std::ostringstream out, err;
  CHECK(cli_main({"run", kExecSource + "/scenarios/wind.toml", "--engine", "/nonexistent/e.toml"},
                 out, err) == kExitBadInput);
  CHECK_THAT(err.str(), Contains("no such engine file"));
}

TEST_CASE(
    "An engine file that is a device or folder, or whose command is a folder, is refused "
    "like a scene file",
    "[exec]") {
  const fs::path dir =
      fs::temp_directory_path() / ("dropcheck_exec_files_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "folder.toml");
  fs::create_directories(dir / "engine_dir");
  fs::create_symlink("/dev/zero", dir / "zero.toml");
  // Refused at once, never read: /dev/zero would never end.
  CHECK_THAT(exec_error_of((dir / "zero.toml").string()),
             Contains("zero.toml: cannot read the file: not a regular file (a device, FIFO or "
                      "socket)"));
  CHECK_THAT(exec_error_of((dir / "folder.toml").string()),
             Contains("folder.toml: cannot read the file: it is a directory"));
  std::ofstream(dir / "e.toml") << "command = [\"./engine_dir\", \"x\"]\n";
  CHECK(exec_error_of((dir / "e.toml").string()) ==
        (dir / "e.toml").string() + ":1: command: './engine_dir' is a folder, not a program");
  std::ofstream(dir / "f.toml") << "command = [\"./missing\"]\n";
  CHECK_THAT(exec_error_of((dir / "f.toml").string()),
             Contains(":1: command: './missing': No such file or directory"));
  std::ofstream(dir / "g.toml") << "name = \"x\"\ncommand = [\"python3\", \"e.py\"]\n"
                                << "# \x1b[2J\n";
  CHECK_THAT(exec_error_of((dir / "g.toml").string()), Contains("g.toml:3: control character"));
  fs::remove_all(dir);
}

TEST_CASE("Two engines that announce the same name are refused as the clash", "[exec][cli]") {
  const fs::path dir =
      fs::temp_directory_path() / ("dropcheck_exec_clash_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string py = kExecSource + "/examples/python/seed_engine.py";
  std::ofstream(dir / "a.toml") << "command = [\"python3\", \"" << py << "\"]\n";
  std::ofstream(dir / "b.toml") << "command = [\"python3\", \"" << py << "\"]\n";
  for (const std::string command : {"run", "check", "report", "bless"}) {
    INFO(command);
    std::ostringstream out, err;
    std::vector<std::string> argv{command,    kExecSource + "/scenarios/free_fall.toml",
                                  "--engine", (dir / "a.toml").string(),
                                  "--engine", (dir / "b.toml").string()};
    if (command == "report" || command == "bless") {
      argv.push_back("--out");
      argv.push_back((dir / ("out-" + command)).string());
    }
    CHECK(cli_main(argv, out, err) == kExitBadInput);
    CHECK_THAT(err.str(), Contains("b.toml'") &&
                              Contains("announces the name 'seed-python', as "
                                       "--engine '") &&
                              Contains("two engines cannot share a name"));
    CHECK_FALSE(fs::exists(dir / ("out-" + command)));
  }
  fs::remove_all(dir);
}

namespace {

using ContactCheck = CheckResult (*)(const Scene&, const EngineFactory&, const Timestep&);

// `check` of the shipped scene `stem` on the test engine tests/adapters/SCRIPT MODE ANNOUNCE.
CheckResult contact_check(ContactCheck check, const char* stem, const char* script,
                          const std::string& mode, const std::string& announce) {
  ExecSpec spec;
  spec.command = {"python3", kExecSource + "/tests/adapters/" + script, mode, announce};
  const Scene s = exec_scene(stem);
  return check(
      s, [&] { return make_exec_engine(spec); }, s.timestep);
}

// The bounce check of scenarios/bounce_e05 on tests/adapters/bounce_engine.py MODE ANNOUNCE.
CheckResult bounce_check(const std::string& mode, const std::string& announce) {
  return contact_check(check_bounce, "bounce_e05", "bounce_engine.py", mode, announce);
}

}  // namespace

TEST_CASE(
    "An external engine that announces restitution and spheres gets the material and the shapes, "
    "and is judged against the bounce law it announces",
    "[exec][contact]") {
  // It follows the ideal law it announces: the figures, to rounding.
  const CheckResult ideal = bounce_check("ideal", "own");
  CHECK(ideal.passed);
  CHECK_THAT(ideal.message, Contains("hits at step 27 at 4.41 m/s, leaves at 2.205 m/s, apexes "
                                     "0.2378") &&
                                Contains("the same path to"));
  // A split-impulse push announced as such passes, with the push named as what moves it.
  const CheckResult split = bounce_check("split", "own");
  CHECK(split.passed);
  CHECK_THAT(split.message, Contains("off the ideal law") && Contains("in position"));
  // The same engine announcing the ideal law is caught at the step after the first contact.
  const CheckResult liar = bounce_check("split", "ideal");
  CHECK_FALSE(liar.passed);
  CHECK_THAT(liar.message, Contains("DEPARTS at step"));
  // An engine without the capabilities never gets the scene.
  ExecSpec plain;
  plain.command = {"python3", kExecSource + "/examples/python/seed_engine.py"};
  CHECK_THAT(make_exec_engine(plain)->cannot_run(exec_scene("bounce_e05")), Contains("contacts"));
}

namespace {

// The slide check of scenarios/slide_stop on tests/adapters/slide_engine.py MODE ANNOUNCE.
CheckResult slide_check(const std::string& mode, const std::string& announce) {
  return contact_check(check_slide, "slide_stop", "slide_engine.py", mode, announce);
}

}  // namespace

TEST_CASE(
    "An external engine declares its contact solver, and a slide is held to Coulomb's law from its "
    "momentum within the bound it declares",
    "[exec][contact]") {
  // Coulomb's cone applied exactly: as the default exact solver it follows the clamp law; as
  // declared sequential impulses or a soft contact its momentum certifies every slipping step.
  const CheckResult exact = slide_check("coulomb", "exact");
  CHECK(exact.passed);
  for (const char* announce : {"sequential", "soft"}) {
    const CheckResult held = slide_check("coulomb", announce);
    INFO(announce << ": " << held.message);
    CHECK(held.passed);
    CHECK_THAT(held.message, Contains("Coulomb's law from its momentum") &&
                                 Contains(std::string(announce) == "soft"
                                              ? "a soft contact (declared)"
                                              : "sequential impulses (10 iterations, declared)"));
    // Its friction 2 % above the scene's mu: beyond the declared bound of 1e-3.
    const CheckResult off = slide_check("mu_off", announce);
    INFO(off.message);
    CHECK_FALSE(off.passed);
    CHECK_THAT(off.message, Contains("another coefficient or combine rule"));
  }
}
