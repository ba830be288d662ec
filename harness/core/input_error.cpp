#include "harness/core/input_error.hpp"

namespace dropcheck {
namespace {

std::string render(const std::string& file, int line, const std::string& key,
                   const std::string& problem) {
  // Appended piece by piece: g++ 12 -O3 warns (-Wstringop-overflow, a false positive) on
  // ":" + std::to_string(line).
  std::string out = file;
  if (line > 0) {
    out += ':';
    out += std::to_string(line);
  }
  if (!out.empty()) out += ": ";
  if (!key.empty()) {
    out += key;
    out += ": ";
  }
  out += problem;
  return out;
}

}  // namespace

InputError::InputError(const std::string& file, int line, const std::string& key,
                       const std::string& problem)
    : std::runtime_error(render(file, line, key, problem)) {}

}  // namespace dropcheck
