// Loads a scene file (TOML; the contract is in docs/design.md "Scenario files") into a validated Scene.
#pragma once

#include <string>

#include "harness/core/input_error.hpp"
#include "harness/core/scene.hpp"

namespace dropcheck {

// Reads and validates `path`. Throws InputError naming the file, line, key and problem for a
// syntax error, an unknown key, a wrong type, a non-finite or out-of-range value, a duplicate or
// unknown body name, both linear_drag and linear_damping, or a step that cannot cover the duration.
Scene load_scene(const std::string& path);

// The same from TOML text; `path` is used in messages and for the default name (the file's stem).
Scene parse_scene(const std::string& text, const std::string& path);

}  // namespace dropcheck
