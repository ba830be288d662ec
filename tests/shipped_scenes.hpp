// The scene files shipped in scenarios/: all of them (any subdirectory), sorted, globbed at test
// time so that a new scene is covered without editing a test; or one, loaded by name.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "harness/scene/scene_loader.hpp"

inline std::vector<std::string> shipped_scenes() {
  std::vector<std::string> files;
  for (const auto& e :
       std::filesystem::recursive_directory_iterator(DROPCHECK_SOURCE_DIR "/scenarios"))
    if (e.is_regular_file() && e.path().extension() == ".toml") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

// Two extreme scenes several tests read.
inline const std::string kTinyStepScene = DROPCHECK_SOURCE_DIR "/scenarios/extreme/tiny_step.toml";
inline const std::string kStiffSpringScene =
    DROPCHECK_SOURCE_DIR "/scenarios/extreme/stiff_spring.toml";

namespace dropcheck::testing {

// scenarios/<stem>.toml, loaded.
inline Scene shipped(const std::string& stem) {
  return load_scene(std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/" + stem + ".toml");
}

}  // namespace dropcheck::testing
