// Tests the dropcheck command line's dispatch and `engines` (harness/cli/cli.cpp, cmd_engines.cpp).
#include "harness/cli/cli.hpp"

#include <catch2/catch.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_driver.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

using dropcheck::testing::cli;
using dropcheck::testing::Result;

}  // namespace

TEST_CASE("engines lists ours in f32 and ours-f64 in f64 with their law and exits 0", "[cli]") {
  const Result r = cli({"engines"});
  CHECK(r.code == 0);
  CHECK(r.err.empty());
  std::istringstream lines(r.out);
  std::string line, ours, ours_f64;
  while (std::getline(lines, line)) {
    if (line.rfind("ours ", 0) == 0) ours = line;
    if (line.rfind("ours-f64 ", 0) == 0) ours_f64 = line;
  }
  CHECK_THAT(ours, Contains(" f32 ") && Contains("v = phi*(v + a*h); x += h*v"));
  CHECK_THAT(ours_f64, Contains(" f64 ") && Contains("v = phi*(v + a*h); x += h*v"));
}

TEST_CASE("an unknown command exits 2 naming it, with the usage on err", "[cli]") {
  const Result r = cli({"frobnicate"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("unknown command 'frobnicate'") && Contains("usage:"));
  CHECK(r.out.empty());
}

TEST_CASE("no command exits 2 with the usage on err, and --help exits 0 with it on out", "[cli]") {
  const Result none = cli({});
  CHECK(none.code == 2);
  CHECK_THAT(none.err, StartsWith("usage:") && Contains("dropcheck run FILE"));
  const Result help = cli({"--help"});
  CHECK(help.code == 0);
  CHECK_THAT(help.out, StartsWith("usage:") && Contains("dropcheck engines"));
}

TEST_CASE("engines with an unknown option exits 2", "[cli]") {
  const Result r = cli({"engines", "--verbose"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--verbose") && Contains("unknown option"));
}
