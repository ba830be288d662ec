#include "harness/core/number_format.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

using namespace dropcheck;

namespace {

// printf's own text, the reference the module must match byte for byte.
std::string printf_g(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

}  // namespace

TEST_CASE("sig, g3, fixed and exact write the bytes printf writes", "[number_format]") {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> values{0.0, -0.0, inf,   -inf,       std::nan(""), 1e300, 5e-324,
                             0.5, 2.5,  9.995, 1.0 / 60.0, 0.0005,       1e16,  123456789.0};
  std::mt19937_64 random(12);
  std::uniform_real_distribution<double> mantissa(-1000.0, 1000.0);
  std::uniform_int_distribution<int> exponent(-40, 40);
  for (int i = 0; i < 2000; ++i) values.push_back(std::ldexp(mantissa(random), exponent(random)));
  for (double v : values) {
    INFO(printf_g(v, 17));
    for (int digits : {2, 3, 4, 6, 9, 15}) CHECK(sig(v, digits) == printf_g(v, digits));
    CHECK(g3(v) == printf_g(v, 3));
    CHECK(exact(v) == printf_g(v, 17));
    char buf[400];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    CHECK(fixed(v, 2) == buf);
  }
}

TEST_CASE("shortest gives the shortest text that reads back", "[number_format]") {
  CHECK(shortest(0.1) == "0.1");
  CHECK(shortest(1.0 / 60.0) == "0.016666666666666666");
  CHECK(shortest(1e10) == "1e+10");
  CHECK(std::strtod(shortest(0.3).c_str(), nullptr) == 0.3);
}

TEST_CASE("lengths are printed in a readable unit", "[number_format]") {
  CHECK(format_length(0.0) == "0 m");
  CHECK(format_length(1.5) == "1.5 m");
  CHECK(format_length(0.0696347) == "6.96 cm");
  CHECK(format_length(0.0025) == "2.5 mm");
  CHECK(format_length(1.23e-5) == "12.3 um");
  CHECK(format_length(3.1e-15) == "3.1e-15 m");
  CHECK(format_length(-0.02) == "-2 cm");
  CHECK(format_length(std::numeric_limits<double>::infinity()) == "inf");
}

TEST_CASE("a divided step keeps the 1/N form while N*n fits, else seconds", "[number_format]") {
  CHECK(divided_step_text("1/60", 1.0 / 60.0, 4) == "1/240");
  CHECK(divided_step_text("0.01", 0.01, 2) == "0.005");
  CHECK(divided_step_text("1/4611686018427387904", 1.0 / 4611686018427387904.0, 4) ==
        "5.42101e-20");
}
