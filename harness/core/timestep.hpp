// Step sizes as users write them: seconds ("0.01", 0.01) or a rate ("1/60").
#pragma once

#include <optional>
#include <string>

#include "harness/core/scene.hpp"

namespace dropcheck {

// Parses "1/N" (N a positive integer) or a decimal number of seconds. Returns nullopt, with the
// problem in `why`, for anything else, zero, negatives and non-finite values. A rate's text is
// written without leading zeros ("1/060" is "1/60"); seconds keep the text given ("1e-5").
std::optional<Timestep> parse_timestep(const std::string& text, std::string& why);

// The largest step count a run may ask for (duration / h).
inline constexpr long long kMaxSteps = 20'000'000;

// Why `h` cannot step through `duration` ("" when it can): h > duration, not a whole number of
// steps, or more than kMaxSteps steps.
std::string step_problem(double duration, double h);

}  // namespace dropcheck
