// Tests `dropcheck report --reference E`: the divergences are measured from the engine asked for
// and every header names it; an engine the report does not run is refused before any work.
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "cli_driver.hpp"
#include "tests/harness/test_dirs.hpp"
#include "tests/scene_texts.hpp"

using Catch::Matchers::Contains;
using namespace dropcheck::testing;

namespace {

// A cube falling half a second, written in `d`.
std::string reference_scene(const ScratchDir& d) {
  return d.write("fall.toml",
                 scene_head("0.5", "1/60", kEarth) + body_text("cube", "[0.0, 10.0, 0.0]", kZero));
}

// The README.md of `report SCENE --out DIR/r ARGS... --no-timing`, which must succeed.
std::string report_of(const ScratchDir& d, std::vector<std::string> args) {
  std::vector<std::string> argv{"report", reference_scene(d), "--out", d.file("r")};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.push_back("--no-timing");
  const Result r = cli(argv);
  REQUIRE(r.code == 0);
  return slurp(d.file("r/README.md"));
}

}  // namespace

TEST_CASE("report --reference measures the divergences from the engine asked for",
          "[cli][report]") {
  ScratchDir d("report-reference");
  const std::string md =
      report_of(d, {"--engine", "ours-f64", "--engine", "ode", "--reference", "ode"});
  CHECK_THAT(md, Contains("#### Divergence from ode at h = 1/60"));
  CHECK_THAT(md, !Contains("Divergence from ours-f64"));
  // Every header names it: the summary's column and note, the introduction, the method.
  CHECK_THAT(md, Contains("| max divergence from ode |") &&
                     Contains("over the run from ode at the same step") &&
                     Contains("and against ode, and the divergence") &&
                     Contains("- Divergence: distance from ode at the same step"));
  CHECK_THAT(md, !Contains("from ours-f64") && !Contains("against ours-f64"));
}

TEST_CASE("report without ours-f64 measures from the first engine given and says so everywhere",
          "[cli][report]") {
  ScratchDir d("report-reference-first");
  const std::string md = report_of(d, {"--engine", "ode", "--engine", "ours"});
  CHECK_THAT(md, Contains("| max divergence from ode |") &&
                     Contains("#### Divergence from ode at h = 1/60"));
  CHECK_THAT(md, !Contains("ours-f64"));
}

TEST_CASE("report --reference with an engine it does not run is refused before any work",
          "[cli][report]") {
  ScratchDir d("report-reference-bad");
  const std::string scene = reference_scene(d);
  const Result r = cli({"report", scene, "--out", d.file("r"), "--engine", "ours-f64",
                        "--reference", "ode", "--no-timing"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--reference ode") && Contains("not one of the engines"));
  CHECK(!std::filesystem::exists(d.file("r")));
}
