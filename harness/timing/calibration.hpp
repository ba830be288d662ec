// The calibration loop: a fixed piece of floating-point work, timed in every round of a timing
// cell beside the engines (timing.hpp), so that each engine's cost can be stated as a ratio to
// something measured on the same machine, at the same moment. It depends on no engine and on
// nothing a change to dropcheck's physics would touch, so the ratio moves only when the engine
// does.
#pragma once

namespace dropcheck {

// Particles and steps of one calibration run: semi-implicit Euler with a linear drag on 1024
// particles (48 KiB of positions and velocities, cache-resident like an engine's bodies) for 512
// steps, 0.5 M particle-steps: 0.36-0.45 ms on this project's 2-core VM (median 0.365 ms over the
// 1376 rounds of the committed report).
inline constexpr int kCalibrationParticles = 1024;
inline constexpr int kCalibrationSteps = 512;

// Runs the loop once and returns its wall time in seconds.
double time_calibration();

}  // namespace dropcheck
