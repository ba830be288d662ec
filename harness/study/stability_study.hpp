// The stability study of one scene on a set of engines: each engine's verdict at the scene's step,
// its error against the analytic oracle there, its largest stable step (search) and, for springs,
// the theoretical edge of its damping order. Used by `dropcheck stability` and the report section.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "harness/judge/metrics.hpp"
#include "harness/judge/stability_classify.hpp"
#include "harness/study/evaluate.hpp"
#include "harness/study/stability_search.hpp"

namespace dropcheck {

// One engine on one scene.
struct EngineStability {
  std::string engine;
  std::string
      skipped;  // why it did not run the scene ("no contacts", "not compiled in"); "" if it ran
  Scalar scalar = Scalar::f64;
  Law law;
  RunStatus status = RunStatus::ok;
  std::int64_t steps_run = 0;             // last step recorded at the scene's step
  Verdict verdict;                        // at the scene's step
  std::optional<ErrorStats> vs_analytic;  // worst body, at the scene's step; none without oracle
  std::optional<StepSearch> search;       // largest stable step; none when not searched
  std::optional<double> theory_max_dt;    // spring edge of this engine's damping order

  bool ran() const { return skipped.empty(); }
  std::string label() const { return engine_label(engine, scalar); }
};

// One scene on every engine asked for.
struct SceneStability {
  std::string name;
  std::string source;  // the scene file
  std::string description;
  Timestep h;               // the scene's step
  double duration = 0.0;    // s
  std::int64_t steps = 0;   // at h
  std::string no_analytic;  // why there is no analytic oracle; "" when there is one
  std::vector<EngineStability> engines;
};

// What the study does besides the run at the scene's step.
struct StudyOptions {
  bool search = true;  // search the largest stable step per engine
  SearchOptions search_options;
  ClassifyOptions classify;
};

// Studies `scene` on the engines passed in (engine slots: the caller makes them, so only those
// run), in the order given. Writes one line per engine to `progress` when not null. A slot without
// a factory comes back skipped with its reason.
SceneStability study_scene(const Scene& scene, const std::vector<EngineSlot>& engines,
                           const StudyOptions& options = {}, std::ostream* progress = nullptr);

}  // namespace dropcheck
