// InputError: bad input (a scene file, a flag) named precisely enough to fix: file, key, problem.
// The CLI prints what() and exits with code 2.
#pragma once

#include <stdexcept>
#include <string>

namespace dropcheck {

struct InputError : std::runtime_error {
  // Renders "FILE:LINE: KEY: PROBLEM", leaving out the parts that are empty or zero.
  InputError(const std::string& file, int line, const std::string& key, const std::string& problem);
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace dropcheck
