#include "harness/scene/scene_files.hpp"

#include <algorithm>
#include <filesystem>

#include "harness/core/input_error.hpp"

namespace dropcheck {

namespace fs = std::filesystem;

std::vector<std::string> toml_files(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && e.path().extension() == ".toml")
      out.push_back(e.path().generic_string());
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> scene_files(const std::vector<std::string>& args) {
  std::vector<std::string> out;
  for (const std::string& arg : args) {
    std::error_code ec;
    if (fs::is_directory(arg, ec)) {
      const std::vector<std::string> found = toml_files(arg);
      if (found.empty()) throw InputError(arg, 0, "", "a folder without a scene file (*.toml)");
      out.insert(out.end(), found.begin(), found.end());
    } else {
      out.push_back(arg);  // its reader says why it cannot be read, if it cannot
    }
  }
  return out;
}

}  // namespace dropcheck
