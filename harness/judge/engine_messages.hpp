// What an engine printed during a run (Trajectory::messages, kept by isolated runs), with what its
// adapter says the lines mean (EngineInfo::known_messages): the cause a departing contact verdict
// names when no member of its law family explains the run, and the report's count of them.
#pragma once

#include <string>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

// The meaning `info` declares for `line`; "" when it declares none.
std::string message_meaning(const EngineInfo& info, const std::string& line);

// "ode printed 'ODE message 3: LCP internal error, s <= 0' once: ODE's LCP solver
// ..."; "" when the run printed nothing.
std::string engine_said(const Trajectory& run, const EngineInfo& info);

}  // namespace dropcheck
