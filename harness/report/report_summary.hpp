// The ten-second view of a scene (report_summary.cpp): the summary table's row and the one-word
// cause of a divergence.
#pragma once

#include <string>

#include "harness/study/evaluate.hpp"

namespace dropcheck {

// The figures the summary table shows for one scene (report_summary.cpp prints them).
struct SceneSummary {
  std::string engines_run;  // "5/6"
  std::string divergence;   // "bullet 6.96 cm", or "—"
  std::string cause;        // one word: damping-order, precision, identical, UNEXPLAINED, ...
                            // (+ rotational law when two turning engines' members differ)
  std::string verdict;      // "ok", or the flags that need a person ("UNEXPLAINED: ode")
};

// The summary figures of one evaluated scene.
SceneSummary summarize(const SceneEvaluation& se);

// One word for why `engine` diverges from the reference at the default step ("precision +
// rotational law" when the positions differ by rounding and the rotational members differ).
std::string divergence_cause(const SceneEvaluation& se, const EngineEvaluation& engine);

}  // namespace dropcheck
