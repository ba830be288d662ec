// Oracle 1: the continuous model's exact solution, where one exists. Contact-free scenes only.
//
// Every dynamic body obeys  m*x'' = m*g + F - S*(x - A) - C*x' - m*k*x'
// with F the sum of its constant forces, and S, A, C the combined stiffness, anchor and dashpot of
// its springs (all rest_length 0: S = sum s_i, A = sum s_i*a_i / S, C = sum c_i). Per axis that is
//   no spring:  x'' = a - k*x'                      (a = g + F/m)
//   spring:     x'' + 2*zeta*w*x' + w^2*(x - x_eq) = 0   (w^2 = S/m, 2*zeta*w = C/m + k,
//                                                         x_eq = A + (m*g + F)/S)
// Both are solved in closed form below; springs with rest_length > 0 are nonlinear: no oracle.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {

// Why `scene` has no closed-form solution ("contacts", "spring with rest length"); empty if it has.
std::string analytic_unavailable(const Scene& scene);

// The exact state of body `index` at time t. Precondition: analytic_unavailable(scene).empty().
BodyState analytic_state(const Scene& scene, std::size_t index, double t);

// A continuous answer `state(body, t)` sampled at the steps a run at h records every `every` steps
// (and the last), as a trajectory named `engine`: analytic_trajectory's and contact_closed_form's.
Trajectory sampled_answer(const Scene& scene, double h, std::int64_t every, const char* engine,
                          const std::function<BodyState(std::size_t, double)>& state);

// The exact solution sampled at the steps a run at h records; nullopt when there is none.
std::optional<Trajectory> analytic_trajectory(const Scene& scene, double h,
                                              const RunOptions& options = {});

}  // namespace dropcheck
