// Loads a scene file (TOML; every key in docs/scene-keys.md, the rules in docs/design.md "Scenario
// files") into a validated Scene.
#pragma once

#include <string>

#include "harness/core/input_error.hpp"
#include "harness/core/scene.hpp"

namespace dropcheck {

// Reads and validates `path`. Throws InputError naming the file, line, key and problem for a
// syntax error, an unknown key, a wrong type, a non-finite or out-of-range value, a duplicate or
// unknown body name, both linear_drag and linear_damping, a step that cannot cover the duration, or
// an [expect] table or description placeholder load_expect refuses (expect_table.hpp). The
// description comes back with its {placeholders} replaced by the [expect] figures' text.
// Only a regular file of at most kMaxSceneBytes is read (see read_scene_text).
Scene load_scene(const std::string& path);

// Largest scene file read: 1 MiB (the shipped scenes are under 2 KiB).
inline constexpr long long kMaxSceneBytes = 1 << 20;

// The bytes of the scene file `path`. Throws InputError, before reading anything, for a path that
// is not a regular file (directory, device such as /dev/zero, FIFO, socket) or is larger than
// kMaxSceneBytes, and when the file grows past that while being read.
std::string read_scene_text(const std::string& path);

// The same from TOML text; `path` is used in messages and for the default name (the file's stem).
Scene parse_scene(const std::string& text, const std::string& path);

}  // namespace dropcheck
