// The checks made before a run starts, in one place: a run that would exceed the step limit, the
// memory budget for its recorded samples, or (for an f32 engine) the float range is refused with a
// message saying which limit and by how much, instead of being started.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "harness/core/engine.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {

// Bytes the recorded samples of one run may take (Trajectory::states and ::recorded): 1 GiB.
inline constexpr std::int64_t kTrajectoryBudgetBytes = std::int64_t{1} << 30;

// Samples a run of `steps` steps records when keeping every `record_every`th step (plus step 0 and
// the last step).
std::int64_t recorded_samples(std::int64_t steps, std::int64_t record_every);

// Bytes those samples take for `bodies` bodies (and their rotational states when `rotates`).
double trajectory_bytes(double samples, std::size_t bodies, bool rotates = false);

// Why the run cannot start ("" when it can): more than kMaxSteps steps
// (harness/core/timestep.hpp), recorded samples over kTrajectoryBudgetBytes, or, for an f32
// engine, a scene value whose magnitude exceeds the largest float (3.4e38), which would become Inf
// inside the engine.
std::string run_refusal(const EngineInfo& engine, const Scene& scene, double h,
                        const RunOptions& options);

// run_refusal as a refused Trajectory, or nullopt when the run may start.
std::optional<Trajectory> refuse_run(const EngineInfo& engine, const Scene& scene, double h,
                                     const RunOptions& options);

}  // namespace dropcheck
