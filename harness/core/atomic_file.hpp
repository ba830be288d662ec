// Output files are written whole or not at all: into a temporary beside the target, then renamed.
#pragma once

#include <string>

namespace dropcheck {

// Writes `content` to `path` atomically. Throws InputError naming the path when it cannot.
void write_file_atomic(const std::string& path, const std::string& content);

}  // namespace dropcheck
