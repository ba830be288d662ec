// The report's count of what the engines printed (Trajectory::messages, kept by isolated runs):
// each engine's distinct lines over every run of the report, with what its adapter says they mean
// (harness/judge/engine_messages.hpp), in place of the lines themselves on the terminal.
#pragma once

#include <string>

#include "harness/report/report.hpp"

namespace dropcheck {

// "## What the engines printed" with its table; "" when no run printed anything.
std::string engine_messages_section(const ReportInput& in);

}  // namespace dropcheck
