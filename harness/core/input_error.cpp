#include "harness/core/input_error.hpp"

namespace dropcheck {
namespace {

std::string render(const std::string& file, int line, const std::string& key,
                   const std::string& problem) {
  std::string out = file;
  if (line > 0) out += ":" + std::to_string(line);
  if (!out.empty()) out += ": ";
  if (!key.empty()) out += key + ": ";
  return out + problem;
}

}  // namespace

InputError::InputError(const std::string& file, int line, const std::string& key,
                       const std::string& problem)
    : std::runtime_error(render(file, line, key, problem)) {}

}  // namespace dropcheck
