// Tests the commands end to end on a scene that aborts Box2D
// (tests/scenes/box2d_tiny_cube_abort.toml) with runs isolated, as the dropcheck executable runs
// them: box2d's run is a "crashed" result in run's summary and JSON, check, report and stability,
// and every other engine's results are kept.
#include <catch2/catch.hpp>
#include <regex>
#include <sstream>

#include "../test_dirs.hpp"
#include "harness/cli/cli.hpp"
#include "harness/core/registry.hpp"
#include "harness/run/isolated_run.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;
using dropcheck::testing::ScratchDir;
using dropcheck::testing::slurp;

namespace {

const std::string kIsolationScene =
    std::string(DROPCHECK_SOURCE_DIR) + "/tests/scenes/box2d_tiny_cube_abort.toml";

// Runs a command with isolated runs (the executable's default), returning its exit code.
int isolated_cli(const std::vector<std::string>& argv, std::string& out_text) {
  set_default_isolation(Isolation::child_process);
  std::ostringstream out, err;
  const int rc = cli_main(argv, out, err);
  set_default_isolation(Isolation::in_process);
  out_text = out.str() + err.str();
  return rc;
}

bool have(const std::string& engine) {
  return engine_unavailable_reason(engine).empty();
}

}  // namespace

TEST_CASE(
    "run on a scene that aborts Box2D reports box2d crashed and keeps the other engines' results",
    "[cli][isolation]") {
  if (!have("box2d")) return;
  ScratchDir dir("isolation-run");
  std::string out;
  REQUIRE(isolated_cli({"run", kIsolationScene, "--json", dir.file("runs.json")}, out) == kExitOk);
  INFO(out);
  CHECK_THAT(out, Contains("box2d  crashed: SIGABRT while loading the scene"));
  CHECK_THAT(out, Contains("Assertion `area > "));
  for (const std::string e : {"bullet", "ode", "mujoco"})
    if (have(e)) CHECK(std::regex_search(out, std::regex("\n" + e + " +cube +-?[0-9]")));
  const std::string json = slurp(dir.file("runs.json"));
  CHECK_THAT(json, Contains("\"status\":\"crashed\""));
  CHECK_THAT(json, Contains("\"status\":\"ok\""));
}

TEST_CASE("check, report and stability carry box2d's crash as its result", "[cli][isolation]") {
  if (!have("box2d")) return;
  ScratchDir dir("isolation-cmds");
  std::string out;
  isolated_cli({"check", kIsolationScene, "--engine", "box2d"}, out);
  CHECK_THAT(out, Contains("crashed: SIGABRT while loading the scene"));
  REQUIRE(isolated_cli({"report", kIsolationScene, "--out", dir.file("report"), "--no-timing",
                        "--engine", "box2d", "--engine", "ode"},
                       out) == kExitOk);
  CHECK_THAT(slurp(dir.file("report/README.md")), Contains("failed"));
  isolated_cli({"stability", kIsolationScene, "--engine", "box2d"}, out);
  CHECK_THAT(out, Contains("crashed"));
}
