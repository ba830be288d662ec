// One scene's section of the report (report_scene.cpp) and the summary row it contributes.
#pragma once

#include <string>

#include "harness/oracles/landing.hpp"
#include "harness/report/report.hpp"

namespace dropcheck {

// The figures the summary table shows for one scene (report_summary.cpp prints them).
struct SceneSummary {
  std::string engines_run;  // "5/6"
  std::string divergence;   // "bullet 6.96 cm", or "—"
  std::string cause;        // one word: damping-order, precision, identical, UNEXPLAINED, ...
  std::string verdict;      // "ok", or the flags that need a person ("UNEXPLAINED: ode")
};

// The summary figures of one evaluated scene.
SceneSummary summarize(const SceneEvaluation& se);

// One word for why `engine` diverges from the reference at the default step.
std::string divergence_cause(const SceneEvaluation& se, const EngineEvaluation& engine);

// The scene's section: what it tests and leaves out, plots, divergence with attribution, errors
// against each oracle, error against run time, observed orders, failures.
std::string scene_section(const SceneEvaluation& se, const std::vector<ReportPlot>& plots,
                          const PlotOutcomes& outcomes, bool timing);

// The landing table of a contact scene at the default step ("" when no body lands on a floor).
std::string landing_section(const SceneEvaluation& se);

// True when the run's resting offset lies within the engine's documented band.
bool rest_offset_expected(const EngineEvaluation& ev, const LandingResult& landing);

// How the default-step run's passage through the floor is judged, as `dropcheck check` judges it
// (judge_tunnelling, harness/oracles/landing.hpp): limit = tunnelled without continuous collision.
TunnelVerdict landing_tunnel_verdict(const SceneEvaluation& se, const EngineEvaluation& ev,
                                     const LandingResult& landing);

// The Markdown anchor GitHub gives a heading ("Free fall (drag)" -> "free-fall-drag").
std::string heading_anchor(const std::string& heading);

}  // namespace dropcheck
