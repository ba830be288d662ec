// Tests harness/core/timestep.cpp: step texts ("1/N" or seconds) and the step-count rules.
#include "harness/core/timestep.hpp"

#include <catch2/catch.hpp>
#include <string>

using Catch::Matchers::Contains;

namespace {

// The parse problem for `text`, or "(parsed)" when it parses.
std::string why_not(const std::string& text) {
  std::string why;
  return dropcheck::parse_timestep(text, why) ? "(parsed)" : why;
}

}  // namespace

TEST_CASE("1/N and decimal seconds parse to their value and keep their text", "[timestep]") {
  std::string why;
  const auto rate = dropcheck::parse_timestep("1/60", why);
  REQUIRE(rate);
  CHECK(rate->seconds == 1.0 / 60.0);
  CHECK(rate->text == "1/60");
  const auto secs = dropcheck::parse_timestep("0.01", why);
  REQUIRE(secs);
  CHECK(secs->seconds == 0.01);
  CHECK(dropcheck::parse_timestep("1e-3", why)->seconds == 0.001);
  CHECK(dropcheck::parse_timestep("1/240", why)->seconds == 1.0 / 240.0);
}

TEST_CASE("1/0, 1/-60, 1/60.5, abc, -0.1, 0, inf and nan are rejected with the text quoted",
          "[timestep]") {
  CHECK_THAT(why_not("1/0"), Contains("positive whole number") && Contains("\"1/0\""));
  CHECK_THAT(why_not("1/-60"), Contains("positive whole number"));
  CHECK_THAT(why_not("1/60.5"), Contains("positive whole number"));
  CHECK_THAT(why_not("1/"), Contains("positive whole number"));
  CHECK_THAT(why_not("abc"), Contains("expected seconds") && Contains("\"abc\""));
  CHECK_THAT(why_not("0.01s"), Contains("expected seconds"));
  CHECK_THAT(why_not(""), Contains("expected seconds"));
  CHECK_THAT(why_not("-0.1"), Contains("> 0") && Contains("\"-0.1\""));
  CHECK_THAT(why_not("0"), Contains("> 0"));
  CHECK_THAT(why_not("inf"), Contains("finite"));
  CHECK_THAT(why_not("nan"), Contains("finite"));
}

TEST_CASE("a step that covers the duration in whole steps has no problem", "[timestep]") {
  CHECK(dropcheck::step_problem(1.0, 1.0 / 60.0) == "");
  CHECK(dropcheck::step_problem(1.0, 1.0) == "");
  // 3.0 / 0.1 = 29.999999999999996 in double: decimal steps are whole to rounding.
  CHECK(dropcheck::step_problem(3.0, 0.1) == "");
}

TEST_CASE("a step longer than the duration or not dividing it is a problem", "[timestep]") {
  CHECK_THAT(dropcheck::step_problem(0.01, 1.0 / 60.0), Contains("longer than the duration"));
  CHECK_THAT(dropcheck::step_problem(2.0, 0.7), Contains("not a whole number of steps"));
  CHECK_THAT(dropcheck::step_problem(1.0, 1.0 / 60.0 * 1.001),
             Contains("not a whole number of steps"));
}

TEST_CASE("kMaxSteps steps are allowed and one more is not", "[timestep]") {
  const double h = 1.0 / 64.0;  // exact, so the counts are exact
  CHECK(dropcheck::step_problem(dropcheck::kMaxSteps * h, h) == "");
  CHECK_THAT(dropcheck::step_problem((dropcheck::kMaxSteps + 1) * h, h),
             Contains("20000001 steps, more than the limit of 20000000"));
}
