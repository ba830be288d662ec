// The one run loop: load a scene into an engine, step it, sample the trajectory.
#pragma once

#include <cstdint>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

// Where a run's engine steps (harness/run/isolated_run.hpp).
enum class Isolation {
  process_default,  // whatever set_default_isolation() chose for this process (in_process unless
                    // set)
  in_process,       // in this process: fastest; an engine's abort ends the program
  child_process,  // in a forked child: a crash, hang or runaway allocation becomes the run's status
};

struct RunOptions {
  std::int64_t record_every = 1;  // keep every Nth step (and always step 0 and the last step)
  Isolation isolation = Isolation::process_default;
  // Wall-clock limit: a child process is killed at it (<= 0: the default, 600 s); a run in this
  // process with a limit > 0 checks it after every step (a step that never returns is not caught).
  double time_limit_seconds = 0.0;
};

// Runs `scene` on `engine` at step h for step_count(scene, h) steps. Each step: forces from the
// state at the start of the step (harness/core/forces.hpp), set_forces, step, read. A NaN/Inf
// state, an EngineError, an allocation failure, a refusal (harness/run/run_limits.hpp) and,
// isolated, a crash or time-out end the run and are recorded in the trajectory's status; it never
// throws for them.
Trajectory run_scene(Engine& engine, const Scene& scene, double h, const RunOptions& options = {});

// The same loop in this process, without the pre-checks: what run_scene and an isolated child run.
Trajectory run_scene_in_process(Engine& engine, const Scene& scene, double h,
                                const RunOptions& options = {});

}  // namespace dropcheck
