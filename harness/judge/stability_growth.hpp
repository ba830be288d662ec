// Unbounded growth (stability_growth.cpp): energy or speed beyond what the physics allows.
#pragma once

#include <vector>

#include "harness/judge/stability_classify.hpp"

namespace dropcheck::stability_detail {

// Appends the growth failures of `run`: spring energy, free-flight speed, contact-scene energy,
// and the rotational energy of a turning body in free flight.
void find_growth(const Scene& scene, const Trajectory& run, const ClassifyOptions& o,
                 std::vector<Failure>& out);

}  // namespace dropcheck::stability_detail
