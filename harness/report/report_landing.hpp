// The landing part of a contact scene's section of the report (report_landing.cpp).
#pragma once

#include <string>

#include "harness/oracles/landing.hpp"
#include "harness/study/evaluate.hpp"

namespace dropcheck {

// The landing table of a contact scene at the default step ("" when no body lands on a floor).
std::string landing_section(const SceneEvaluation& se);

// How the default-step run's passage through the floor is judged, as `dropcheck check` judges it
// (judge_tunnelling, harness/oracles/landing.hpp): limit = tunnelled without continuous collision.
TunnelVerdict landing_tunnel_verdict(const SceneEvaluation& se, const EngineEvaluation& ev,
                                     const LandingResult& landing);

}  // namespace dropcheck
