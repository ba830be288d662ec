// Trajectories out: CSV (one row per body per recorded step) and JSON, numbers printed with %.17g
// so that they read back exactly.
#pragma once

#include <ostream>
#include <span>
#include <string>

#include "harness/core/trajectory.hpp"

namespace dropcheck {

// Header "engine,dt,step,t,body,x,y,z,vx,vy,vz", then rows, step 0 being the initial state. When
// some run rotates (Trajectory::rotates) every row adds "qw,qx,qy,qz,wx,wy,wz" (orientation and
// world-frame angular velocity; a run that does not rotate writes 1,0,0,0,0,0,0).
std::string trajectories_to_csv(std::span<const Trajectory> runs);

// The same CSV written row by row to `out` (for a file: memory stays one row, not the whole text).
void write_trajectories_csv(std::ostream& out, std::span<const Trajectory> runs);

// {"runs":[{"engine","scene","dt","steps","status",...,"bodies":[...]}]} with every sample; a
// rotating run's samples add [qw,qx,qy,qz] and [wx,wy,wz] after the velocity.
std::string trajectories_to_json(std::span<const Trajectory> runs);

// The same JSON written piece by piece to `out` (memory stays one sample's text).
void write_trajectories_json(std::ostream& out, std::span<const Trajectory> runs);

}  // namespace dropcheck
