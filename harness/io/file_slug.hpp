// The one rule that turns a user's name (scene, engine) into a file name: the report's plots and
// the guard's baselines both use it, so a name means the same file everywhere.
#pragma once

#include <cstddef>
#include <string>

namespace dropcheck {

// Letters, digits, '-', '_' and '.' kept, every other byte (including '/', NUL) '_'; a leading '.'
// (or an empty name) gets a '_' in front, so "../x" -> "_.._x" cannot leave its folder or hide.
// Not one-to-one ("a/b" and "a_b" meet): writers refuse collisions (harness/guard/bless.hpp).
// A slug longer than kMaxSlugBytes keeps its first bytes and ends in '~' and 16 hex digits of the
// FNV-1a hash of the whole name, kMaxSlugBytes in all: a file system takes names of 255 bytes, and
// a baseline is "<scene>.<engine>.txt" with a temporary ".<that>.tmp-XXXXXX" beside it. The '~'
// occurs in no other slug, so a shortened name never meets a short one.
inline constexpr std::size_t kMaxSlugBytes = 100;
std::string file_slug(const std::string& name);

}  // namespace dropcheck
