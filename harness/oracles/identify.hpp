// Identify an unknown fixed-step integrator from a free-flight trajectory alone: fit every member
// of the discrete-law family (harness/core/law.hpp) with its own per-step damping factor phi and
// gravity g, and name the member that reproduces the trajectory.
//
// Fit, per member, on the velocity sequence (forces F from the scene, on the recorded states):
//   after-forces type  (after-forces, after-position, after-forces/explicit):
//       v[n+1] = phi*(v[n] + h*F/m) + c,   c = phi*h*g
//   before-forces type (before-forces, before-forces/explicit):
//       v[n+1] - h*F/m = phi*v[n] + c,      c = h*g
//   RK4: v[n+1] - h*T*F/m = phi*v[n] + c,  c = h*T*g, phi = R(k*h), T = T(k*h) (law.hpp), refitted
//       three times with T from the last phi
// All are linear in (phi, c_x, c_y, c_z): least squares over every step, body and component.
// When the velocities do not change (a force-free run, or one at its terminal velocity) phi and c
// are not determined: the fit says so (determined = false) and reports no figure for them.
// Then the member is iterated from the recorded initial state with the fitted phi and g (forces on
// its own predicted states), and its residual is the largest |x - prediction| over the run.
// A member whose velocity update matches but whose position update does not (after-position vs
// after-forces: x moves by h*v' or h*phi*v') is caught by the positions.
// Limits: with g fitted, after-forces with gravity g and before-forces with gravity phi*g give the
// same trajectory unless a force acts that differs between bodies (wind.toml), so a gravity-only
// scene reports those two as ambiguous.
#pragma once

#include <string>
#include <vector>

#include "harness/core/law.hpp"
#include "harness/core/scene.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

// A member fits when it reproduces every position to within this (m).
inline constexpr double kIdentifyTolerance = 0.02;

// One member of the family fitted to the trajectory.
struct MemberFit {
  Law law;
  double phi = 1.0;             // fitted per-step velocity factor (when determined)
  Vec3 gravity = Vec3::Zero();  // fitted gravity (m/s^2) (when determined)
  bool determined = true;       // the run determines phi and gravity (its velocities change)
  double max_dx = 0.0;          // largest |x - prediction| over samples, bodies, components (m)
  double max_dv = 0.0;          // the same for velocities (m/s)
};

// Every member's fit and the verdict.
struct Identification {
  std::vector<MemberFit> fits;    // one per kLawFamily member, in family order
  std::size_t best = 0;           // index in fits of the smallest max_dx
  std::size_t runner_up = 0;      // index of the second smallest
  bool fits_any = false;          // fits[best].max_dx <= kIdentifyTolerance
  std::vector<std::size_t> tied;  // the members within 2x (+1e-12 m) of the best, best first
  bool ambiguous = false;         // more than one member is tied: no verdict
  bool determined = true;         // every member's phi and gravity are determined by the run
};

// Identifies the law behind `run`, a run of `scene` at step run.h with every step recorded from 0.
// Throws InputError when the run cannot be used: contacts, failed run, fewer than 3 steps, a gap in
// the recorded steps, bodies that differ from the scene's, no dynamic body.
Identification identify_law(const Scene& scene, const Trajectory& run);

}  // namespace dropcheck
