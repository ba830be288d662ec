// The scene files a command's arguments name, the same for every command that takes them: a file
// as given, a folder as the *.toml files directly in it (sorted by name, so that the order does
// not depend on the disk).
#pragma once

#include <string>
#include <vector>

namespace dropcheck {

// The *.toml regular files directly in `dir`, sorted by name; empty when there are none or `dir`
// cannot be read.
std::vector<std::string> toml_files(const std::string& dir);

// Each argument expanded: a folder to toml_files, anything else kept (the scene reader names what
// is wrong with it). Throws InputError naming a folder without a *.toml file in it.
std::vector<std::string> scene_files(const std::vector<std::string>& args);

}  // namespace dropcheck
