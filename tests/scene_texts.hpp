// Scene files a test writes inline, built from one spelling of their parts: a head (duration, time
// step, [world]) and [[body]] tables, to which a test appends its own [[force]] tables. Vectors and
// numbers are given as TOML text, so the scene reads as the file the loader is handed.
#pragma once

#include <string>

namespace dropcheck::testing {

// TOML for the zero vector, the usual start position and the "no gravity" world.
inline const std::string kZero = "[0.0, 0.0, 0.0]";
// TOML for Earth's gravity along -y, the shipped scenes' world.
inline const std::string kEarth = "[0.0, -9.8, 0.0]";

// The top of a scene file: `duration` seconds, `timestep` ("" leaves the loader's default 1/60),
// and a [world] table with `gravity` and any further `world` lines (e.g. "linear_drag = 0.98\n").
inline std::string scene_head(const std::string& duration, const std::string& timestep,
                              const std::string& gravity, const std::string& world = "") {
  std::string text = "duration = " + duration + "\n";
  if (!timestep.empty()) text += "timestep = \"" + timestep + "\"\n";
  return text + "[world]\ngravity = " + gravity + "\n" + world;
}

// One [[body]] table: `name` at `position`, moving at `velocity` ("" leaves it at rest), and any
// further `extra` lines (e.g. "static = true\n", "mass = 2.0\n").
inline std::string body_text(const std::string& name, const std::string& position,
                             const std::string& velocity = "", const std::string& extra = "") {
  std::string text = "[[body]]\nname = \"" + name + "\"\nposition = " + position + "\n";
  if (!velocity.empty()) text += "velocity = " + velocity + "\n";
  return text + extra;
}

}  // namespace dropcheck::testing
