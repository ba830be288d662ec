// The scene files shipped in scenarios/ (any subdirectory), sorted: globbed at test time, so a new
// scene is covered without editing a test.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

inline std::vector<std::string> shipped_scenes() {
  std::vector<std::string> files;
  for (const auto& e :
       std::filesystem::recursive_directory_iterator(DROPCHECK_SOURCE_DIR "/scenarios"))
    if (e.is_regular_file() && e.path().extension() == ".toml") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  return files;
}
