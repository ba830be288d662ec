// The one rule that turns a user's name (scene, engine) into a file name: the report's plots and
// the guard's baselines both use it, so a name means the same file everywhere.
#pragma once

#include <string>

namespace dropcheck {

// Letters, digits, '-', '_' and '.' kept, every other byte (including '/', NUL) '_'; a leading '.'
// (or an empty name) gets a '_' in front, so "../x" -> "_.._x" cannot leave its folder or hide.
// Not one-to-one ("a/b" and "a_b" meet): writers refuse collisions (harness/guard/bless.hpp).
std::string file_slug(const std::string& name);

}  // namespace dropcheck
