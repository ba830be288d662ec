// Tests harness/io/trajectory_csv.cpp, the reader of `identify --trajectory`: numbers that are not
// numbers (NaN, infinities) are refused with line and column before any fit, a UTF-8 byte-order
// mark is accepted, and a refusal quotes only a short, escaped excerpt of the file.
#include "harness/io/trajectory_csv.hpp"

#include <catch2/catch.hpp>
#include <sstream>
#include <string>

#include "harness/core/input_error.hpp"

using Catch::Matchers::Contains;
using namespace dropcheck;

namespace {

const std::string kHeader = "engine,dt,step,t,body,x,y,z,vx,vy,vz\n";
const std::string kRow0 = "e,0.5,0,0,c,0,10,0,0,0,0\n";

std::vector<Trajectory> parse(const std::string& text) {
  std::istringstream in(text);
  return parse_trajectories_csv(in, "run.csv");
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(read)";
}

}  // namespace

TEST_CASE("a NaN or infinite number in any numeric column is refused with line and column",
          "[csv]") {
  CHECK(error_of(kHeader + kRow0 + "e,0.5,1,0.5,c,nan,10,0,0,0,0\n") ==
        "run.csv:3: x (column 6): 'nan' is not a finite number (no verdict can be fitted to it)");
  CHECK_THAT(error_of(kHeader + kRow0 + "e,0.5,1,0.5,c,0,10,0,0,-inf,0\n"),
             Contains("run.csv:3: vy (column 10): '-inf' is not a finite number"));
  CHECK_THAT(error_of(kHeader + "e,0.5,0,inf,c,0,10,0,0,0,0\n"),
             Contains("run.csv:2: t (column 4): 'inf' is not a finite number"));
  CHECK_THAT(error_of(kHeader + "e,NaN,0,0,c,0,10,0,0,0,0\n"),
             Contains("run.csv:2: dt (column 2): 'NaN' is not a finite number"));
  CHECK_THAT(error_of(kHeader + "e,1e999,0,0,c,0,10,0,0,0,0\n"),
             Contains("run.csv:2: dt (column 2): '1e999' is not a number"));
  CHECK(error_of(kHeader + kRow0 + "e,0.5,1,0.5,c,0,9,0,0,-1,0\n") == "(read)");
  // Each number finite, but step x dt, the time dropcheck uses, is not.
  CHECK_THAT(
      error_of(kHeader + "e,1e308,0,0,c,0,10,0,0,0,0\ne,1e308,2,0,c,0,10,0,0,0,0\n"),
      Contains("run.csv:3: step (column 3): step x dt is not a finite time ('2' x '1e308')"));
  // CRLF line ends, the last line without one.
  CHECK(parse(kHeader + "e,0.5,0,0,c,0,10,0,0,0,0\r\ne,0.5,1,0.5,c,0,9,0,0,-1,0\r").size() == 1);
}

TEST_CASE("a UTF-8 byte-order mark before the header is accepted, as in scenes", "[csv]") {
  const std::vector<Trajectory> runs = parse("\xef\xbb\xbf" + kHeader + kRow0);
  REQUIRE(runs.size() == 1);
  CHECK(runs[0].engine == "e");
  CHECK(runs[0].at(0, 0).position.y() == 10.0);
  // Anywhere else it is not the header.
  CHECK_THAT(error_of("x\xef\xbb\xbf" + kHeader + kRow0), Contains("the header must be"));
}

TEST_CASE("a refusal quotes a short, escaped excerpt, never the field or line whole", "[csv]") {
  const std::string field(50'000, '7');
  const std::string huge = error_of(kHeader + "e,0.5,0,0,c," + field + "x,10,0,0,0,0\n");
  CHECK_THAT(huge, Contains("x (column 6): '777"));
  CHECK_THAT(huge, Contains("... (50001 bytes) is not a number"));
  CHECK(huge.size() < 200);
  const std::string line(70'000, 'a');
  CHECK(error_of(kHeader + line + "\n") ==
        "run.csv:2: a line longer than 64 KiB: not a trajectory CSV");
  CHECK(error_of(kHeader + "e,0.5,0,0,c,\x1b[2J,10,0,0,0,0\n") ==
        "run.csv:2: x (column 6): '\\x1b[2J' is not a number");
}

TEST_CASE("an engine or body name with a control character is refused", "[csv]") {
  CHECK_THAT(error_of(kHeader + "\"e\x1b]0;owned\x07\",0.5,0,0,c,0,10,0,0,0,0\n"),
             Contains("run.csv:2: engine (column 1): 'e\\x1b]0;owned\\x07' is not a name"));
  CHECK_THAT(error_of(kHeader + "e,0.5,0,0,\"a\tb\",0,10,0,0,0,0\n"),
             Contains("run.csv:2: body (column 5): 'a\\x09b' is not a name"));
}
