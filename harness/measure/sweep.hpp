// The timestep sweep of a scene and the order of convergence measured over it: built once here for
// `report`, `check`, the regression tiers and the adapter tests.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "harness/core/scene.hpp"

namespace dropcheck {

// The steps a scene is measured at, largest first, the default step included, duplicates removed:
// the scene's `timesteps`; a scene with fewer than two gets h, h/2 and h/4 (an order needs two).
std::vector<Timestep> scene_sweep(const Scene& scene);

// Index of the scene's default step in scene_sweep(scene).
std::size_t default_index(const std::vector<Timestep>& sweep, const Scene& scene);

// The steps the own-law check runs at: the default step and the next two of the sweep.
std::vector<Timestep> own_law_steps(const Scene& scene);

// Observed orders over a sweep p_i = ln(e_i/e_{i+1}) / ln(h_i/h_{i+1}), judged.
struct OrderEstimate {
  std::vector<double> orders;  // one per consecutive pair
  bool measurable = false;     // every error above `noise` (else rounding bends the curve)
  bool first_order = false;    // every order within tolerance::kFirstOrderLow..High
  bool consistent = false;     // every order at or above tolerance::kConsistentOrder
  std::string text;            // "max |dx| 1.2 cm, 6 mm at h = 1/30, 1/60; observed orders 1.002"
};

// Judges errors e (m) at steps h; errors at or below `noise` (m) make the order not measurable.
OrderEstimate estimate_order(std::span<const double> h, std::span<const double> e, double noise);

// True when a and b are the same step (to 1e-12 relative).
bool same_step(double a, double b);

}  // namespace dropcheck
