// Distances between two trajectories of one scene, and the observed order of convergence.
#pragma once

#include <span>
#include <vector>

#include "harness/core/trajectory.hpp"

namespace dropcheck {

// |dx| and |dv| (Euclidean, m and m/s) of one body over the samples two trajectories share in time.
struct ErrorStats {
  double max_dx = 0.0, rms_dx = 0.0, final_dx = 0.0;
  double max_dv = 0.0, rms_dv = 0.0, final_dv = 0.0;
  double final_t = 0.0;       // time of the last shared sample (s)
  double diverged_at = -1.0;  // first t where |dx| > tolerance; -1 when never
  std::size_t samples = 0;    // shared samples compared
};

// Compares body `body` of `a` against `b` at every sample time present in both (the two may run at
// different h: a fine-step reference is sampled at the coarse run's times). Samples are matched
// when their times agree to 1e-9 of the coarser step. Failed runs compare up to their last sample.
ErrorStats compare(const Trajectory& a, const Trajectory& b, std::size_t body, double tolerance);

// The worst ErrorStats over all dynamic bodies (by max |dx|), for one-line summaries.
ErrorStats compare_worst(const Trajectory& a, const Trajectory& b, double tolerance);

// Observed order of convergence between consecutive sweep points: p = ln(e1/e2) / ln(h1/h2).
// `h` and `error` are parallel; the result has one entry fewer (NaN where an error is zero).
std::vector<double> observed_orders(std::span<const double> h, std::span<const double> error);

}  // namespace dropcheck
