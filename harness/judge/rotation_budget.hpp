// What a run did to one turning body's conserved quantities, and how it compares with the closed
// form of torque-free rotation (harness/oracles/free_rotation.hpp): the report's rotation section.
//
// With R the rotation of q, I the principal moments and w the world angular velocity:
//   L = R*diag(I)*R^T*w           world angular momentum (constant without torque)
//   E_rot = w.L/2                 rotational energy (constant without torque and damping)
//   E_lin = m*v^2/2 - m*g.x       translational plus potential energy (constant in free flight)
// Changes are signed, end minus start: > 0 the run gained energy, < 0 it lost it. Keeping the two
// energies apart is what lets a reader see a rotation gain or lose energy: summed, the
// translational part (semi-implicit Euler's g*h*t/2 drift of the potential) hides it.
#pragma once

#include <cstddef>
#include <vector>

#include "harness/core/trajectory.hpp"

namespace dropcheck {

struct RotationBudget {
  double momentum_drift = 0.0;            // max over samples of |L(t) - L(0)| / |L(0)|
  double rotational_energy = 0.0;         // E_rot at the start (J)
  double rotational_energy_change = 0.0;  // E_rot(end) - E_rot(start) (J)
  double linear_energy_change = 0.0;      // E_lin(end) - E_lin(start) (J)
  // Against the closed form, when no torque or contact acts on the body (NaN otherwise; angular
  // damping is part of the closed form, rotation_budget.cpp): the
  // largest |w_body - w_closed| (rad/s), and the times at which the body-frame component along the
  // intermediate axis changes sign (interpolated between samples), beside the closed form's.
  double closed_form_error = 0.0;
  std::vector<double> flips, closed_form_flips;
  bool closed_form = false;
};

// The budget of body `body` (dynamic) of `run`, a rotating run of `scene` that finished.
RotationBudget rotation_budget(const Scene& scene, const Trajectory& run, std::size_t body);

}  // namespace dropcheck
