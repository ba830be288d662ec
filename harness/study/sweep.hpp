// The timestep sweep of a scene and the order of convergence measured over it: built once here for
// `report`, `check`, the regression tiers and the adapter tests.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "harness/core/scene.hpp"
#include "harness/judge/tolerances.hpp"

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

// Why a first-order law may not yet show its order at steps down to h on `scene`: the products of
// the scene's rates and h at its finest step that are not small (k*h; omega*h and the dashpot's
// gamma*h per spring; the phase drift omega*T*(relative frequency error of semi-implicit Euler))
// as "k*h = 0.5 at h = 0.008333 s". Each product above tolerance::kPreAsymptoticProduct is
// named; if none is, the largest.
std::string pre_asymptotic_cause(const Scene& scene, double h);

// A sweep whose order was out of band, extended with halvings of its finest step.
struct ExtendedSweep {
  std::vector<double> h, e;  // the scene's sweep, then each added step and its error
  std::size_t added = 0;     // steps added
  OrderEstimate estimate;    // over all of h and e
  bool reached = false;      // the last order is measurable and within the first-order band
  std::string stopped;       // why it stopped short of the band ("" when reached)
};

// The error at step h (m), or nullopt with the reason in `why` (a run failed, it left its law).
using ErrorAt = std::function<std::optional<double>(double h, std::string& why)>;

// Halves the finest step of (h, e) until the last observed order is in band, within the step
// limit (kMaxSteps per run) and `max_added` steps per sweep in all.
ExtendedSweep extend_sweep(const Scene& scene, std::vector<double> h, std::vector<double> e,
                           double noise, const ErrorAt& error_at,
                           std::int64_t max_added = tolerance::kExtensionSteps);

// "1/480" when h is 1/N for a whole N, else "%.4g".
std::string step_text(double h);

// True when a and b are the same step (to 1e-12 relative).
bool same_step(double a, double b);

}  // namespace dropcheck
