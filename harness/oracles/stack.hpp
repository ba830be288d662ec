// A resting stack of boxes on a static floor: the ideal answer (every body at its geometric rest
// height, nothing moving) and what an engine's stack law (harness/core/stack_law.hpp) adds to it,
// per body: the sink of every contact under it, its rest offsets, and whether an iterative solver
// can hold the load at all (docs/contact.md "Stacks").
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/scene.hpp"

namespace dropcheck {

// One body of a column, bottom up.
struct StackLevel {
  std::size_t body = 0;      // index into Scene::bodies
  int level = 1;             // 1 on the floor, 2 on the body under it, ...
  double rest_height = 0.0;  // m: floor top + the heights of the bodies under it + its half height
  double mass = 0.0;         // kg
  double load = 0.0;         // kg its lower contact carries: its mass and the masses above it
  double mass_below = 0.0;   // kg: the body it rests on (0: the static floor)
};

// A column of dynamic, unturned boxes over one static floor box, each over the top face of the
// one under it (its centre strictly inside that face), at rest (or dropped from rest onto the body
// under it), no force on them, gravity straight down, contacts on, and no other body sharing a
// member's footprint above the floor (its load or its obstruction would go uncounted). Two or more
// bodies: one body alone is a landing (harness/oracles/landing.hpp).
struct StackSetup {
  std::size_t body = 0;  // its bottom body, which names the column
  std::size_t floor = 0;
  double floor_top = 0.0;          // m
  double g = 0.0;                  // m/s^2, straight down
  double damping_rate = 0.0;       // 1/s, the scene's drag
  std::vector<StackLevel> levels;  // bottom up
};

std::vector<StackSetup> stack_setups(const Scene& scene);

// What the engine's stack law predicts for one level at step h.
struct StackPrediction {
  double sink = 0.0;    // m: the steady-state sink of the contacts under it, summed
  double offset = 0.0;  // m: its rest offsets (EngineInfo::rest_offset per contact)
  // The largest sweep residual of the contacts under it (StackLaw::sweep_residual): over 1/2, the
  // solver cannot hold the load, a named limit.
  double residual = 0.0;
  double load = 0.0, mass = 0.0;  // kg: the load and the body of the contact with that residual
};
StackPrediction predict_stack(const StackSetup& setup, std::size_t level, const EngineInfo& info,
                              double h);

// The residual past which a solver is not expected to hold a stack.
inline constexpr double kUnheldResidual = 0.5;

}  // namespace dropcheck
