// The rotation part of a rotating scene's section of the report (report_rotation.cpp).
#pragma once

#include <string>

#include "harness/study/evaluate.hpp"

namespace dropcheck {

// For a scene that needs rotation: each engine's rotational bookkeeping over the sweep (momentum
// drift, signed rotational and translational energy changes, distance to the torque-free closed
// form), the Dzhanibekov flip times against the closed form, and the figures published for the
// scene beside the member that predicts each and today's engines. "" for any other scene.
std::string rotation_section(const SceneEvaluation& se);

}  // namespace dropcheck
