// Trajectories in: the CSV that `dropcheck run --csv` writes (harness/io/trajectory_io.hpp), read
// back exactly (numbers through std::from_chars), for commands that analyse a recorded run.
#pragma once

#include <string>
#include <vector>

#include "harness/core/trajectory.hpp"

namespace dropcheck {

// The runs in `file`, one per (engine, dt), in order of first appearance; each sample holds every
// body named in that run's first step. Throws InputError (file, line, column, problem) for a
// missing file, a wrong header, a malformed number or a step whose bodies differ from the first
// step's.
std::vector<Trajectory> read_trajectories_csv(const std::string& file);

}  // namespace dropcheck
