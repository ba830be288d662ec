// Failures of motion (stability_motion.cpp): tunnelling and frozen coordinates.
#pragma once

#include <vector>

#include "harness/judge/stability_classify.hpp"

namespace dropcheck::stability_detail {

// Appends a failure for each body that passed through (or sank into) a body it started above.
void find_tunnelling(const Scene& scene, const Trajectory& run, std::vector<Failure>& out);

// Appends a failure for each coordinate held constant by precision while the physics moves it.
void find_frozen(const Scene& scene, const Trajectory& run, Scalar scalar, const ClassifyOptions& o,
                 std::vector<Failure>& out);

}  // namespace dropcheck::stability_detail
