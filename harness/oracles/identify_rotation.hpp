// Identify the rotational member (harness/core/rotation_law.hpp) behind a rotating free-flight
// trajectory alone: replay every member from the trajectory's first sample (its orientation and
// angular velocity; the moments, torques and angular damping rate from the scene) and name the one
// that reproduces every orientation. Each is tried with the orientation turned by the new and by
// the step-start angular velocity (the linear member's position update), and with angular damping
// at every placement of the damping factor too (each member of the linear family, law.hpp); without
// angular damping its placement leaves no trace and only the after-forces placement is tried.
#pragma once

#include <vector>

#include "harness/core/rotation_law.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

// A member fits when it reproduces every orientation to within this angle (rad). Rounding keeps a
// double engine within 6e-10 rad of its member over Gazebo's tumbling box (10 s at h = 1e-3); the
// members differ there by 1.1e-4 rad and more.
inline constexpr double kIdentifyRotationTolerance = 1e-6;

struct RotationFit {
  RotationLaw law;
  Law linear = DampingOrder::AfterForces;  // the placement: damping order and position update
  double max_angle = 0.0;                  // largest geodesic angle to the replay (rad)
  double max_dw = 0.0;                     // largest |w - w_replay| (rad/s)
};

struct RotationIdentification {
  std::vector<RotationFit> fits;  // every member (x every damping placement with angular damping)
  bool damping_seen = false;      // the scene has angular damping: placements were told apart
  std::size_t best = 0, runner_up = 0;
  bool fits_any = false;   // fits[best].max_angle <= kIdentifyRotationTolerance
  bool ambiguous = false;  // the runner-up is within 2x (+1e-12 rad) of the best
};

// Identifies the rotational member behind `run` (which rotates) of `scene`, every step recorded
// from 0. Throws InputError when the run does not rotate.
RotationIdentification identify_rotation(const Scene& scene, const Trajectory& run);

}  // namespace dropcheck
