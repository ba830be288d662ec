// The slowdown alert as a user meets it: `dropcheck report --compare-timings FILE
// --fail-on-slowdown` exits 1 and names the cells that slowed beyond their engine's threshold, 0
// when none did; a bad FILE is refused before any work (exit 2).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_driver.hpp"
#include "harness/io/json_text.hpp"
#include "harness/report/timing_record.hpp"
#include "tests/harness/test_dirs.hpp"
#include "tests/scene_texts.hpp"

using Catch::Matchers::Contains;
using dropcheck::testing::body_text;
using dropcheck::testing::cli;
using dropcheck::testing::kEarth;
using dropcheck::testing::kZero;
using dropcheck::testing::Result;
using dropcheck::testing::scene_head;
using dropcheck::testing::ScratchDir;
using dropcheck::testing::slurp;

namespace {

// `record` with every engine sample of every cell scaled by `factor` (the calibration kept).
std::string scaled_record(const std::string& record, double factor) {
  nlohmann::ordered_json j = dropcheck::parse_json<nlohmann::ordered_json>(record);
  for (auto& cell : j["cells"])
    for (auto& x : cell["samples_ms"]) x = x.get<double>() * factor;
  return dropcheck::json_text(j);
}

}  // namespace

TEST_CASE("report --fail-on-slowdown exits 1 naming the cells that slowed, 0 when none did",
          "[cli][timing]") {
  ScratchDir d("report-slowdown");
  const std::string scene = d.write("fall.toml", scene_head("0.5", "1/60", kEarth) +
                                                     body_text("cube", "[0.0, 10.0, 0.0]", kZero));
  // --timing-smoke: the plumbing, not the figures (a full timing of ours under the sanitizers at
  // -O0 takes minutes).
  const std::vector<std::string> report{"report",   scene,      "--out",         d.file("r"),
                                        "--engine", "ours-f64", "--timing-smoke"};
  REQUIRE(cli(report).code == 0);
  const std::string record = slurp(d.file("r/timings.json"));
  // The same cells, as if measured on a build 100 times as fast: now every cell is far slower (a
  // margin no noise of these smoke timings reaches).
  std::ofstream(d.file("faster.json")) << scaled_record(record, 0.01);
  std::vector<std::string> args = report;
  args.insert(args.end(), {"--compare-timings", d.file("faster.json"), "--fail-on-slowdown"});
  const Result slow = cli(args);
  CHECK(slow.code == 1);
  CHECK_THAT(slow.err,
             Contains("slowdown: fall / ours-f64 / h = 1/60: minimum / calibration rose"));
  CHECK_THAT(slurp(d.file("r/README.md")), Contains("cells are flagged"));
  // Against a build 100 times as slow nothing is flagged.
  std::ofstream(d.file("slower.json")) << scaled_record(record, 100.0);
  args[args.size() - 2] = d.file("slower.json");
  const Result fine = cli(args);
  CHECK(fine.code == 0);
  CHECK(fine.err.find("slowdown:") == std::string::npos);
  CHECK_THAT(slurp(d.file("r/README.md")), Contains("No cell is flagged"));
  CHECK_THAT(fine.err, Contains("slowdown alert: 3 of 3 cells judged, 0 flagged"));
  // A record none of whose cells match (another scene): the gate judged nothing, and says so.
  nlohmann::ordered_json other = dropcheck::parse_json<nlohmann::ordered_json>(record);
  for (auto& cell : other["cells"]) cell["scene"] = "another";
  std::ofstream(d.file("other.json")) << dropcheck::json_text(other);
  args[args.size() - 2] = d.file("other.json");
  const Result none = cli(args);
  CHECK(none.code == 2);
  CHECK_THAT(none.err, Contains("0 of 3 cells judged") && Contains("no cell of this report"));
  // A record from another machine (the far faster one, on another installation): nothing is
  // judged, no slowdown line; the gate refuses to pass on it.
  nlohmann::ordered_json elsewhere =
      dropcheck::parse_json<nlohmann::ordered_json>(scaled_record(record, 0.01));
  elsewhere["machine"]["installation"] = "0123456789abcdef";
  std::ofstream(d.file("elsewhere.json")) << dropcheck::json_text(elsewhere);
  args[args.size() - 2] = d.file("elsewhere.json");
  const Result gate = cli(args);
  CHECK(gate.code == 2);
  CHECK(gate.err.find("calibration rose") == std::string::npos);
  CHECK_THAT(gate.err, Contains("measured on another machine (they differ in installation)"));
  CHECK_THAT(slurp(d.file("r/README.md")), Contains("Not judged: the timings compared with"));
  args.pop_back();  // without --fail-on-slowdown: exit 0
  const Result shown = cli(args);
  CHECK(shown.code == 0);
  CHECK(shown.err.find("slowdown") == std::string::npos);
}

TEST_CASE("report --compare-timings with a bad file is refused before any work", "[cli][timing]") {
  ScratchDir d("report-compare-bad");
  const std::string scene = d.write("fall.toml", scene_head("0.5", "1/60", kEarth) +
                                                     body_text("cube", "[0.0, 10.0, 0.0]", kZero));
  std::ofstream(d.file("bad.json")) << "{\"commit\": 1}";
  const Result r = cli({"report", scene, "--out", d.file("r"), "--engine", "ours-f64",
                        "--compare-timings", d.file("bad.json")});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("bad.json"));
  CHECK(!std::filesystem::exists(d.file("r")));
  const Result none =
      cli({"report", scene, "--out", d.file("r"), "--no-timing", "--fail-on-slowdown"});
  CHECK(none.code == 2);
}
