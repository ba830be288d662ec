// Trajectories out: CSV (one row per body per recorded step) and JSON, numbers printed with %.17g
// so that they read back exactly.
#pragma once

#include <ostream>
#include <span>
#include <string>

#include "harness/core/trajectory.hpp"

namespace dropcheck {

// Header "engine,dt,step,t,body,x,y,z,vx,vy,vz", then rows, step 0 being the initial state.
std::string trajectories_to_csv(std::span<const Trajectory> runs);

// The same CSV written row by row to `out` (for a file: memory stays one row, not the whole text).
void write_trajectories_csv(std::ostream& out, std::span<const Trajectory> runs);

// {"runs":[{"engine","scene","dt","steps","status",...,"final":[...]}]} with every sample.
std::string trajectories_to_json(std::span<const Trajectory> runs);

// The same JSON written piece by piece to `out` (memory stays one sample's text).
void write_trajectories_json(std::ostream& out, std::span<const Trajectory> runs);

}  // namespace dropcheck
