#include "harness/core/number_format.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace dropcheck {

std::string vprintf_string(fmt::string_view pattern, fmt::printf_args args) {
  return fmt::vsprintf(pattern, args);
}

std::string sig(double v, int digits) {
  return fmt::format("{:.{}g}", v, digits);
}

std::string g3(double v) {
  return sig(v, 3);
}

std::string fixed(double v, int decimals) {
  return fmt::format("{:.{}f}", v, decimals);
}

std::string exact(double v) {
  return fmt::format("{:.17g}", v);
}

// std::to_chars, not fmt's "{}": both are shortest, but they switch to exponents at different
// magnitudes (1e10: "1e+10" against "10000000000"), and the scene texts already use to_chars'.
std::string shortest(double v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, ec == std::errc() ? end : buf);
}

std::string format_length(double m) {
  const double x = std::abs(m);
  if (x == 0.0) return "0 m";
  if (!std::isfinite(x)) return "inf";
  if (x >= 1.0) return g3(m) + " m";
  if (x >= 1e-2) return g3(m * 1e2) + " cm";
  if (x >= 1e-3) return g3(m * 1e3) + " mm";
  if (x >= 1e-6) return g3(m * 1e6) + " um";
  return sig(m, 2) + " m";
}

std::string divided_step_text(const std::string& h_text, double h_seconds, long long n) {
  // N*n only while it fits a long long (N = 2^62 once printed 1/-2446744073709551616).
  const long long denominator = std::atoll(h_text.c_str() + 2);
  if (h_text.rfind("1/", 0) == 0 && denominator > 0 && n > 0 &&
      denominator <= std::numeric_limits<long long>::max() / n)
    return "1/" + std::to_string(denominator * n);
  return sig(h_seconds / static_cast<double>(n), 6);
}

}  // namespace dropcheck
