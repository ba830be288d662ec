// Oracle 2 for rotation: an engine's own rotational member (harness/core/rotation_law.hpp),
// iterated in long double from the scene's initial state, and how far a run departs from it.
//
// The departure is measured with metrics that do not lie (harness/core/rotation_metrics.hpp):
// the geodesic angle between the run's orientation and the law's, and |w - w_law|, worst over
// samples and bodies. Free bodies only: contacts are not modelled.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "harness/core/rotation_law.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

// The rotational state of every body of `scene` at each step in `recorded`, under `law` with the
// angular damping and the orientation update placed as the engine's linear member `linear` places
// the linear damping and the position update (advance_rotation), at step h: recorded.size() x
// bodies, sample-major (static bodies keep their start).
std::vector<RotationState> predict_rotation(RotationLaw law, Law linear, const Scene& scene,
                                            double h, const std::vector<std::int64_t>& recorded);

// The same from `start` (one state per body) instead of the scene's initial rotation: a law
// replayed from a recorded trajectory's first sample.
std::vector<RotationState> predict_rotation_from(RotationLaw law, Law linear, const Scene& scene,
                                                 double h,
                                                 const std::vector<std::int64_t>& recorded,
                                                 const std::vector<RotationState>& start);

// How much the law's rotation amplifies a small change of the initial angular velocity: the largest
// ratio, over the run, of the departure it causes (in angle and in |w|/|w0|) to the relative size
// of the change (tried along x, y and z, 1e-9 of |w0|). 1 for a steady spin; a body tumbling near
// its intermediate axis amplifies (Dzhanibekov). Rounding injected at each step grows at most this
// much, which is what the own-law tolerance of a rotation is built from (own_law.hpp).
double rotation_amplification(RotationLaw law, Law linear, const Scene& scene, double h,
                              const std::vector<std::int64_t>& recorded);

// The largest relative drift of body `body`'s world angular momentum, max |L(t) - L(0)|/|L(0)|,
// when member `law` (damping after the forces) runs the scene at step h, every step sampled: what
// a benchmark that publishes this figure for an engine on that member should have measured.
double predicted_momentum_drift(const Scene& scene, RotationLaw law, double h, std::size_t body);

// How far a run's rotation is from a prediction laid out like it.
struct RotationResidual {
  double angle = 0.0;    // max geodesic angle (rad)
  double w = 0.0;        // max |w - w_law| (rad/s)
  double w_scale = 0.0;  // max |w_law|: what the residual in w is relative to
  std::size_t worst_sample = 0, worst_body = 0;  // where the larger of the two (angle, w/scale) is
};

// `run` (which rotates) against `predicted`, laid out like run.rotations (predict_rotation for the
// run's recorded steps, or another run's rotations), over the first `samples` samples (all by
// default). A NaN distance counts as infinite.
RotationResidual rotation_residual(const Trajectory& run, std::span<const RotationState> predicted,
                                   std::size_t samples = SIZE_MAX);

}  // namespace dropcheck
