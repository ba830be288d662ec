// Tests harness/report/sweep_results.cpp, what `report --results` reads: a result file's text is
// read as the file is (a line at a time, "\r\n" and empty lines taken), each field the report
// draws comes from its record, and a line that is not a record is refused naming its line.
#include "harness/report/sweep_results.hpp"

#include <catch2/catch.hpp>
#include <cmath>

#include "harness/core/input_error.hpp"
#include "tests/harness/test_dirs.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;
using dropcheck::testing::ScratchDir;

namespace {

const std::string kOk =
    R"({"format":"dropcheck-record/1","key":"s|ours|timestep=1/60","scene":"s",)"
    R"("engine":{"name":"ours"},"axes":{"timestep":"1/60"},"status":"ok",)"
    R"("error":{"closed_form":{"max_dx":0.5}},"stability":{"theory_max_h":"inf",)"
    R"("law_unstable":""},"timing":{"ns_per_body_step":12.5,"cpu":"x"}})";
const std::string kSkipped =
    R"({"format":"dropcheck-record/1","key":"s|bullet|timestep=1/60","scene":"s",)"
    R"("axes":{"timestep":"1/60"},"status":"skipped","reason":"f64 only"})";

std::string results_error_of(const std::string& text) {
  try {
    parse_sweep_results(text, "r.jsonl");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(read)";
}

}  // namespace

TEST_CASE("a result file's text is read as the file is, a record per line", "[report][results]") {
  const std::string text = "\r\n" + kOk + "\r\n\n" + kSkipped;
  const std::vector<SweepCell> cells = parse_sweep_results(text, "r.jsonl");
  REQUIRE(cells.size() == 2);
  CHECK(cells[0].key == "s|ours|timestep=1/60");
  CHECK(cells[0].engine == "ours");
  CHECK(cells[0].axes == std::vector<std::pair<std::string, std::string>>{{"timestep", "1/60"}});
  CHECK(cells[0].error == 0.5);
  CHECK(std::isinf(cells[0].theory_max_h.value()));
  CHECK(cells[0].ns_per_body_step == 12.5);
  CHECK(cells[0].cpu == "x");
  CHECK(cells[1].engine == "bullet");  // no engine field: taken from the key
  CHECK(cells[1].reason == "f64 only");
  ScratchDir d("sweep-results");
  const std::vector<SweepCell> read = read_sweep_results(d.write("r.jsonl", text));
  REQUIRE(read.size() == 2);
  CHECK(read[0].key == cells[0].key);
  CHECK(read[1].key == cells[1].key);
}

TEST_CASE("a line that is not a record is refused naming its line", "[report][results]") {
  CHECK_THAT(results_error_of(kOk + "\n\n{\"format\":\"dropcheck-record/2\"}\n"),
             Contains("r.jsonl:3: not a dropcheck-record/1 record: '{\"format\""));
  CHECK_THAT(results_error_of(kOk + "\n" + R"({"format":"dropcheck-record/1","key":"s"})"),
             Contains("r.jsonl:2: not a dropcheck-record/1 record"));
  CHECK_THAT(results_error_of("\n\r\n"), Contains("r.jsonl: holds no record"));
  CHECK_THAT(results_error_of(std::string(kMaxResultLine + 1, ' ')),
             Contains("r.jsonl:1: a line longer than 1048576 bytes: not a result file"));
}
