#include "harness/core/timestep.hpp"

#include <charconv>
#include <cmath>

#include "harness/core/number_format.hpp"

namespace dropcheck {
namespace {

bool parse_double(const std::string& s, double& out) {
  const char* end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, out);
  return ec == std::errc() && p == end;
}

}  // namespace

std::optional<Timestep> parse_timestep(const std::string& text, std::string& why) {
  double seconds = 0.0;
  std::string canonical;  // a rate's text: "1/N" without leading zeros
  if (text.rfind("1/", 0) == 0) {
    long long n = 0;
    const char* end = text.data() + text.size();
    auto [p, ec] = std::from_chars(text.data() + 2, end, n);
    if (ec != std::errc() || p != end || n <= 0) {
      why = "expected \"1/N\" with N a positive whole number, got \"" + text + "\"";
      return std::nullopt;
    }
    seconds = 1.0 / static_cast<double>(n);
    canonical = "1/" + std::to_string(n);
  } else if (!parse_double(text, seconds)) {
    why = "expected seconds (0.01) or a rate (\"1/60\"), got \"" + text + "\"";
    return std::nullopt;
  }
  if (!std::isfinite(seconds) || seconds <= 0.0) {
    why = "must be a finite number of seconds > 0, got \"" + text + "\"";
    return std::nullopt;
  }
  return Timestep{seconds, canonical.empty() ? text : canonical};
}

std::string step_problem(double duration, double h) {
  if (h > duration) return "step " + std::to_string(h) + " s is longer than the duration";
  const double n = duration / h;
  if (n > static_cast<double>(kMaxSteps)) {
    // %.15g, not llround: a count beyond 2^63 (duration = 1e300) has no integer to round to.
    return "duration / step = " + sig(std::round(n), 15) + " steps, more than the limit of " +
           std::to_string(kMaxSteps);
  }
  if (std::abs(n - std::round(n)) > 1e-9 * n)
    return "the duration is not a whole number of steps (" + std::to_string(n) + ")";
  return {};
}

}  // namespace dropcheck
