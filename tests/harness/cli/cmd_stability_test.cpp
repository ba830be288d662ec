// Tests harness/cli/cmd_stability.cpp through dropcheck::cli_main: the table on out, progress on
// err, the JSON file (written whole, with max_stable_dt per engine), and exit 2 with
// file/key/problem on bad input.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../test_dirs.hpp"
#include "cli_driver.hpp"
#include "harness/cli/cli.hpp"
#include "tests/shipped_scenes.hpp"

using Catch::Matchers::Contains;
namespace fs = std::filesystem;
using dropcheck::testing::slurp;

namespace {

using dropcheck::testing::cli;
using dropcheck::testing::Result;

}  // namespace

TEST_CASE("stability prints the table and writes max_stable_dt per engine to --json",
          "[cli][stability]") {
  const fs::path dir =
      fs::temp_directory_path() / ("dropcheck_stability_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string json = (dir / "out" / "spring.json").string();
  const Result r = cli(
      {"stability", kStiffSpringScene, "--engine", "ours-f64", "--engine", "ours", "--json", json});
  CHECK(r.code == 0);
  // Measured: 0.033303 for both (bracket [0.033303, 0.0333481] around 2/omega = 0.0333333).
  CHECK_THAT(r.out, Contains("ours-f64 (f64)   stable            0.033303       0.0333333"));
  CHECK_THAT(r.out, Contains("ours (f32)"));
  CHECK_THAT(r.err, Contains("stability stiff_spring: ours-f64 (f64) stable"));
  const std::string text = slurp(json);
  CHECK_THAT(text, Contains("\"engine\":\"ours-f64\"") && Contains("\"max_stable_dt\":0.0333030") &&
                       Contains("\"theory_max_dt\":0.03333333") &&
                       Contains("\"limit\":\"unbounded growth\""));
  CHECK_FALSE(fs::exists(json + ".tmp"));
  fs::remove_all(dir);
}

TEST_CASE("stability on bad input exits 2 naming the file, key or engine", "[cli][stability]") {
  const Result missing = cli({"stability", "no/such/extreme.toml"});
  CHECK(missing.code == 2);
  CHECK_THAT(missing.err, Contains("no/such/extreme.toml") && Contains("cannot read"));
  const Result engine = cli({"stability", kStiffSpringScene, "--engine", "warp-drive"});
  CHECK(engine.code == 2);
  CHECK_THAT(engine.err, Contains("--engine warp-drive") && Contains("unknown engine"));
  const Result usage = cli({"stability"});
  CHECK(usage.code == 2);
  CHECK_THAT(usage.err, Contains("stability") && Contains("exactly one scene FILE"));
  const Result option = cli({"stability", kStiffSpringScene, "--dt", "1/60"});
  CHECK(option.code == 2);
  CHECK_THAT(option.err, Contains("--dt") && Contains("unknown option"));
}
