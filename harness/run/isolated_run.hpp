// Isolated runs: each engine run in a forked child process, so that an engine's abort, segfault,
// runaway allocation or endless loop becomes that run's status ("crashed: SIGABRT at step 12",
// "timed out at step 40") instead of the end of dropcheck. The child runs the ordinary in-process
// loop (run_scene_in_process) on its copy of the engine, counts completed steps in a shared page
// and sends the Trajectory back over a pipe (harness/io/trajectory_wire.hpp); its stderr (an
// engine's warnings, an assertion message, a sanitizer report) is kept as counted lines
// (Trajectory::messages) instead of flooding ours, and its last line quoted in a failure. No
// threads: safe with AddressSanitizer.
#pragma once

#include "harness/run/runner.hpp"

namespace dropcheck {

// Wall-clock limit of one isolated run when RunOptions::time_limit_seconds is not set.
inline constexpr double kDefaultRunTimeLimitSeconds = 600.0;

// The isolation RunOptions::isolation = process_default stands for (initially in_process; the
// dropcheck executable sets child_process).
void set_default_isolation(Isolation isolation);
Isolation default_isolation();

// True when `options` ask for (or default to) a child process.
bool runs_isolated(const RunOptions& options);

// Runs the scene in this process with the wall-clock limit of options (default
// kDefaultRunTimeLimitSeconds) checked after every step: past it the run ends as timed out (no
// pre-checks: run_scene makes them). For an engine that is a process of its own
// (EngineInfo::own_process), whose parent this process is, and for an in-process run given a limit
// (a sweep's worker).
Trajectory run_own_process(Engine& engine, const Scene& scene, double h, const RunOptions& options);

// Runs the scene in a child process (no pre-checks: run_scene makes them). Never throws for what
// the engine does; the parent's `engine` object is left as it was.
Trajectory run_isolated(Engine& engine, const Scene& scene, double h, const RunOptions& options);

}  // namespace dropcheck
