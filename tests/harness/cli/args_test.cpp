// Tests harness/cli/args.cpp: positionals, repeatable --name VALUE options and --flags, by spec.
#include "harness/cli/args.hpp"

#include <catch2/catch.hpp>

#include "harness/core/input_error.hpp"

using Catch::Matchers::Contains;

namespace {

const dropcheck::CommandSpec kSpec{"demo",
                                   "A demo command.",
                                   "FILE",
                                   "files",
                                   0,
                                   -1,
                                   {{"--engine", "E", "engines", true},
                                    {"--dt", "H", "step"},
                                    {"--csv", "OUT", "csv"},
                                    {"--quick", "", "a flag"}}};

dropcheck::Args parse_args_line(const std::vector<std::string>& argv) {
  return dropcheck::parse_args(kSpec, argv);
}

}  // namespace

TEST_CASE("parse_args splits positionals, repeatable options and flags", "[cli][args]") {
  const dropcheck::Args a = parse_args_line(
      {"scene.toml", "--engine", "ours", "--quick", "--engine", "ode", "more", "--dt", "1/120"});
  CHECK(a.positional == std::vector<std::string>{"scene.toml", "more"});
  CHECK(a.values("--engine") == std::vector<std::string>{"ours", "ode"});
  CHECK(a.value("--engine") == "ode");  // the last one
  CHECK(a.value("--dt") == "1/120");
  CHECK(a.value("--csv", "fallback") == "fallback");
  CHECK(a.values("--csv").empty());
  CHECK(a.has("--quick"));
  CHECK_FALSE(a.has("--csv"));
}

TEST_CASE("a negative number is a value and --name=VALUE takes any value", "[cli][args]") {
  const dropcheck::Args a = parse_args_line({"--dt", "-0.1", "--csv=--out"});
  CHECK(a.value("--dt") == "-0.1");
  CHECK(a.value("--csv") == "--out");
  CHECK(a.positional.empty());
}

TEST_CASE(
    "after a bare -- every word is a positional, and a single-dash word before it is an unknown "
    "option",
    "[cli][args]") {
  const dropcheck::Args a = parse_args_line({"--", "-x"});
  CHECK(a.positional == std::vector<std::string>{"-x"});
  CHECK_THROWS_WITH(parse_args_line({"-x"}), Contains("-x") && Contains("unknown option"));
}

TEST_CASE("an unknown option or a missing value is an InputError naming the option",
          "[cli][args]") {
  CHECK_THROWS_WITH(parse_args_line({"--nope"}), Contains("--nope") && Contains("unknown option"));
  CHECK_THROWS_WITH(parse_args_line({"f.toml", "--dt"}), Contains("--dt"));
  CHECK_THROWS_AS(parse_args_line({"--nope"}), dropcheck::InputError);
}

TEST_CASE("an empty value or a single-valued option given twice is an InputError naming it",
          "[cli][args]") {
  CHECK_THROWS_WITH(parse_args_line({"--dt", ""}), Contains("--dt") && Contains("empty"));
  CHECK_THROWS_WITH(parse_args_line({"--dt", "1", "--dt", "2"}),
                    Contains("--dt") && Contains("2 times"));
}

TEST_CASE("--help is thrown as HelpRequested carrying the options", "[cli][args]") {
  try {
    parse_args_line({"--help"});
    FAIL("no HelpRequested");
  } catch (const dropcheck::HelpRequested& h) {
    CHECK_THAT(h.text, Contains("--engine") && Contains("--dt") && Contains("dropcheck demo"));
  }
}
