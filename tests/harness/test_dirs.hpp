// Helpers shared by the tests that read shipped scenes by name or write files: scratch directories
// and reading a file back whole.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "harness/scene/scene_loader.hpp"

namespace dropcheck::testing {

// A shipped scene, scenarios/<stem>.toml.
inline Scene shipped_scene(const std::string& stem) {
  return load_scene(std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/" + stem + ".toml");
}

// A contact scene ours cannot run (a turning cube beside another dynamic one), for the tests of a
// skipped run: every shipped scene runs on ours.
inline const std::string kTurnedPair =
    std::string(DROPCHECK_SOURCE_DIR) + "/tests/scenes/ours_turned_pair.toml";

// A fresh, empty directory under the system's temporary directory, removed again at scope exit.
struct ScratchDir {
  std::filesystem::path path;
  explicit ScratchDir(const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             ("dropcheck-" + name + "-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  // The path of `name` inside the directory.
  std::string file(const std::string& name) const { return (path / name).string(); }
  // Writes `text` to `name` inside the directory and returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name, std::ios::binary) << text;
    return file(name);
  }
};

// The whole content of a file ("" when it cannot be read).
inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace dropcheck::testing
