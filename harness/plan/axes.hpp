// A sweep cell's scene, step and engine: the plan's scene with the cell's axis values applied.
//
// A key axis sets a number in the scene's TOML before the scene is built and validated, so a value
// the scene file could not hold is refused as the loader refuses it. The path names tables by key,
// array elements by [index], and [[body]] tables also by their name:
//   "duration", "world.linear_drag", "world.gravity[1]", "body.cube.mass", "body[0].velocity[2]",
//   "force[0].spring.stiffness"
// A key that does not exist yet is added to its table (body.cube.friction); a path through
// something missing is refused. Named axes then act on the scene model (sweep_file.hpp says how).
#pragma once

#include <span>
#include <string>

#include "harness/core/scene.hpp"
#include "harness/core/timestep.hpp"
#include "harness/plan/sweep_file.hpp"

namespace dropcheck {

struct CellSetup {
  Scene scene;
  Timestep h;
  std::string engine;  // what runs: the sweep's engine, or its other build for the scalar axis
  std::string scalar;  // "f32" or "f64" when the scalar axis asks for one, else ""
};

// Applies `values` (one per axis, as in cell keys) to the scene `text` of `file` for `engine`.
// Throws InputError (no file or line: the caller names the sweep and axis) when a value cannot
// apply: a key path through nothing, a scene without springs for spring_stiffness, fewer than two
// dynamic bodies for mass_ratio, a negative magnitude, or a scene the value makes invalid.
// Throws InputError unless `text` is a value of `axis` written as the sweep file loader writes it
// (a step's text, "f32"/"f64", or the shortest text of a finite number): a plan read back must not
// name one cell by two keys (" 0.5" and "0.5").
void check_canonical_value(const Axis& axis, const std::string& text);

CellSetup setup_cell(const std::string& text, const std::string& file, const std::string& engine,
                     std::span<const Axis> axes, std::span<const std::string> values);

}  // namespace dropcheck
