// The one run loop: load a scene into an engine, step it, sample the trajectory.
#pragma once

#include <cstdint>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

struct RunOptions {
  std::int64_t record_every = 1;  // keep every Nth step (and always step 0 and the last step)
};

// Runs `scene` on `engine` at step h for step_count(scene, h) steps. Each step: forces from the
// state at the start of the step (harness/core/forces.hpp), set_forces, step, read. A NaN/Inf state or
// an EngineError ends the run and is recorded in the trajectory's status; it never throws for them.
Trajectory run_scene(Engine& engine, const Scene& scene, double h, const RunOptions& options = {});

}  // namespace dropcheck
