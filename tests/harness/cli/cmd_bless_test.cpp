// Tests harness/cli/cmd_bless.cpp and cmd_diff.cpp as a user (or ctest) calls them: exit codes
// 0 passed, 1 failed, 77 skipped, 2 bad usage; --out writes a result set anywhere.
#include <catch2/catch.hpp>
#include <filesystem>
#include <sstream>

#include "../test_dirs.hpp"
#include "harness/cli/cli.hpp"

using namespace dropcheck;
using namespace dropcheck::testing;

namespace {

std::string scene_file(const std::string& stem) {
  return std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/" + stem + ".toml";
}

int run_bless(const std::vector<std::string>& argv, std::string& out) {
  std::ostringstream o, e;
  const int code = cli_main(argv, o, e);
  out = o.str() + e.str();
  return code;
}

}  // namespace

TEST_CASE("bless --out writes a result set that bless --check then passes", "[baseline][cli]") {
  const ScratchDir dir("cli-bless");
  std::string out;
  REQUIRE(
      run_bless({"bless", scene_file("throw_up"), "--engine", "ours", "--out", dir.path.string()},
                out) == 0);
  CHECK_THAT(out, Catch::StartsWith("new ") && Catch::Contains("throw_up.ours.txt (hash "));
  const std::vector<std::string> check = {"bless",          "--check", scene_file("throw_up"),
                                          "--engine",       "ours",    "--baselines",
                                          dir.path.string()};
  REQUIRE(run_bless(check, out) == 0);
  CHECK_THAT(out, Catch::Contains("passed: throw_up / ours / bits: hash ") &&
                      Catch::Contains(
                          "passed: throw_up / ours / determinism: two runs gave identical CSV"));
}

TEST_CASE("bless --check exits 77 when every tier is skipped and 1 when a baseline is missing",
          "[baseline][cli]") {
  const ScratchDir dir("cli-check");
  std::string out;
  CHECK(run_bless(
            {"bless", "--check", kTurnedPair, "--engine", "ours", "--baselines", dir.path.string()},
            out) == 77);
  CHECK_THAT(out, Catch::Contains("skipped: ours_turned_pair / ours / physics: the engine cannot "
                                  "run this scene: a turned or turning box beside another"));
  CHECK(run_bless({"bless", "--check", scene_file("wind"), "--engine", "ours-f64", "--tier",
                   "tolerance", "--baselines", dir.path.string()},
                  out) == 1);
  CHECK_THAT(out,
             Catch::Contains("FAILED: wind / ours-f64 / tolerance: no baseline ") &&
                 Catch::Contains("run `dropcheck bless " + scene_file("wind") + "` to make one"));
  CHECK(run_bless({"bless", "--check", scene_file("wind"), "--tier", "colour"}, out) == 2);
  CHECK(run_bless({"bless", scene_file("wind"), "--tier", "bits"}, out) == 2);
}

TEST_CASE("bless --out writes a run that fails a tier, marks it and exits 1", "[baseline][cli]") {
  const ScratchDir dir("cli-bless-failed");
  const std::string engine =
      std::string(DROPCHECK_SOURCE_DIR) + "/examples/python/wrong_order.toml";
  std::string out;
  CHECK(run_bless(
            {"bless", scene_file("free_fall_drag"), "--engine", engine, "--out", dir.path.string()},
            out) == 1);
  INFO(out);
  CHECK_THAT(out, Catch::Contains("FAILED (written, marked in the file): free_fall_drag / "
                                  "wrong-order / physics: oracle 2") &&
                      Catch::Contains("a consistent new scheme: first-order, follows") &&
                      Catch::Contains("no baseline to compare with"));
  CHECK(std::filesystem::exists(dir.file("free_fall_drag.wrong-order.txt")));
  CHECK(run_bless(
            {"bless", scene_file("free_fall_drag"), "--engine", "ours", "--out", dir.path.string()},
            out) == 0);
}

TEST_CASE("diff prints Markdown to stdout or writes it with --out", "[baseline][cli]") {
  const ScratchDir a("cli-diff-a"), b("cli-diff-b"), c("cli-diff-out");
  std::string out;
  REQUIRE(run_bless({"bless", scene_file("free_fall"), "--out", a.path.string()}, out) == 0);
  REQUIRE(run_bless({"bless", scene_file("free_fall"), "--out", b.path.string()}, out) == 0);
  REQUIRE(run_bless({"diff", a.path.string(), b.path.string()}, out) == 0);
  CHECK_THAT(out, Catch::StartsWith("# dropcheck diff") &&
                      Catch::Contains("0 of 2 scene/engine runs moved"));
  REQUIRE(run_bless({"diff", a.path.string(), b.path.string(), "--out", c.file("diff.md")}, out) ==
          0);
  CHECK_THAT(slurp(c.file("diff.md")), Catch::Contains("| free_fall | ours | identical |"));
  CHECK(run_bless({"diff", a.path.string()}, out) == 2);
}
