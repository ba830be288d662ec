// One scene's section of the report (report_scene.cpp).
#pragma once

#include <string>

#include "harness/report/report.hpp"

namespace dropcheck {

// The scene's section: what it tests and leaves out, plots, divergence with attribution, errors
// against each oracle, error against run time, observed orders, failures.
std::string scene_section(const SceneEvaluation& se, const std::vector<ReportPlot>& plots,
                          const PlotOutcomes& outcomes, bool timing);

// The Markdown anchor GitHub gives a heading ("Free fall (drag)" -> "free-fall-drag").
std::string heading_anchor(const std::string& heading);

}  // namespace dropcheck
