// Tests harness/cli/args.cpp: positionals, repeatable --name VALUE options and --flags.
#include <catch2/catch.hpp>

#include "harness/cli/args.hpp"
#include "harness/core/input_error.hpp"

using Catch::Matchers::Contains;

TEST_CASE("parse_args splits positionals, repeatable options and flags", "[cli][args]") {
  const dropcheck::Args a = dropcheck::parse_args(
      {"scene.toml", "--engine", "ours", "--quick", "--engine", "ode", "more", "--dt", "1/120"},
      {"--engine", "--dt"}, {"--quick"});
  CHECK(a.positional == std::vector<std::string>{"scene.toml", "more"});
  CHECK(a.values("--engine") == std::vector<std::string>{"ours", "ode"});
  CHECK(a.value("--engine") == "ode");  // the last one
  CHECK(a.value("--dt") == "1/120");
  CHECK(a.value("--csv", "fallback") == "fallback");
  CHECK(a.values("--csv").empty());
  CHECK(a.has("--quick"));
  CHECK_FALSE(a.has("--csv"));
}

TEST_CASE("an option's value is taken verbatim even when it looks like an option or a negative number", "[cli][args]") {
  const dropcheck::Args a = dropcheck::parse_args({"--dt", "-0.1", "--csv", "--out"}, {"--dt", "--csv"}, {});
  CHECK(a.value("--dt") == "-0.1");
  CHECK(a.value("--csv") == "--out");
  CHECK(a.positional.empty());
}

TEST_CASE("single-dash words and a bare -- are positionals", "[cli][args]") {
  const dropcheck::Args a = dropcheck::parse_args({"--", "-x"}, {}, {});
  CHECK(a.positional == std::vector<std::string>{"--", "-x"});
}

TEST_CASE("an unknown option or a missing value is an InputError naming the option", "[cli][args]") {
  CHECK_THROWS_WITH(dropcheck::parse_args({"--nope"}, {"--dt"}, {}), Contains("--nope") && Contains("unknown option"));
  CHECK_THROWS_WITH(dropcheck::parse_args({"f.toml", "--dt"}, {"--dt"}, {}), Contains("--dt") && Contains("expects a value"));
  CHECK_THROWS_AS(dropcheck::parse_args({"--nope"}, {}, {}), dropcheck::InputError);
}
