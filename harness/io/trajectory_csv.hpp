// Trajectories in: the CSV that `dropcheck run --csv` writes (harness/io/trajectory_io.hpp), read
// back exactly (numbers through std::from_chars), for commands that analyse a recorded run; and
// the per-run CSV log of Gazebo's physics benchmark (scpeters/benchmark tools/mcap_to_csv.py: a
// line "physics_engine,time_step,...", its values, then sim_time, model_no, world linear and
// angular velocity, position and quaternion w x y z per model per step), turned from Gazebo's
// z-up frame into dropcheck's y-up one by the proper rotation (x, y, z) -> (x, z, -y), its models
// named model_0, model_1, ... and its steps counted from its first row.
#pragma once

#include <istream>
#include <string>
#include <vector>

#include "harness/core/trajectory.hpp"

namespace dropcheck {

// The runs in `file`, one per (engine, dt), in order of first appearance; each sample holds every
// body named in that run's first step. Throws InputError (file, line, column, problem) for a
// missing file or one that is not a regular file, a wrong header (a UTF-8 byte-order mark before
// it is accepted), a line over 64 KiB, a malformed or non-finite number (NaN, inf) in any numeric
// column, or a step whose bodies differ from the first step's. Messages quote only short, escaped
// excerpts of the file (harness/core/input_error.hpp).
std::vector<Trajectory> read_trajectories_csv(const std::string& file);

// The same from a stream; `file` names it in messages (what the fuzz target reads).
std::vector<Trajectory> parse_trajectories_csv(std::istream& in, const std::string& file);

}  // namespace dropcheck
