// Evaluation of one scene on every engine, for the comparison report: each engine over the scene's
// timestep sweep, measured against the three oracles kept apart (docs/design.md "Oracles"):
//   1. continuous analytic solution (harness/oracles/analytic.hpp), where one exists;
//   2. the engine's own discrete law (harness/oracles/discrete_law.hpp), for free flight (no
//   contacts);
//   3. self-consistency: the same engine at a much finer step, where no closed form exists;
// and against the reference engine (ours-f64) at the same step, split into law part and residual
// (harness/judge/attribution.hpp). Timed apart, all scenes at once (time_evaluations).
// Engine-neutral: engines come in as named factories, so the harness does not depend on adapters.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"
#include "harness/judge/attribution.hpp"
#include "harness/judge/landing_expectation.hpp"
#include "harness/judge/metrics.hpp"
#include "harness/judge/own_law.hpp"
#include "harness/oracles/landing.hpp"
#include "harness/timing/timing.hpp"

namespace dropcheck {

// One engine as the caller knows it: a factory, or the reason there is none ("not compiled in").
struct EngineSlot {
  std::string name;
  EngineFactory make;       // empty when the engine is not available in this build
  std::string unavailable;  // why `make` is empty
};

struct EvaluateOptions {
  std::string reference = "ours-f64";  // divergences are measured from this engine
  int fine_factor = 8;                 // oracle 3 runs at (finest step of the sweep) / fine_factor
};

// One body's landing in one run (contact scenes): what the run shows against what the continuous
// model (setup.contact_time) and the engine's own discrete law (contacts ignored) expect.
struct LandingResult {
  LandingSetup setup;
  LandingObservation seen;
  double law_contact_time =
      0.0;  // s: the law's first step with the bottom at the floor * h; NaN never
  LandingExpectation expected;  // its rest offset, or its engine's climb path
  LandingEnd end;               // how the run's end meets that
};

// One engine at one step h of the sweep.
struct StepEvaluation {
  Timestep h;
  Trajectory run;
  std::optional<ErrorStats> vs_analytic;      // oracle 1, worst body
  std::optional<ErrorStats> vs_law;           // oracle 2, worst body
  double law_budget = 0.0;                    // own_law_tolerance(...).x: how far vs_law may go
  std::optional<OwnLawVerdict> own_law;       // the own-law verdict (harness/judge/own_law.hpp)
  std::optional<ErrorStats> vs_fine;          // oracle 3, worst body
  std::optional<ErrorStats> vs_reference;     // divergence from the reference engine, worst body
  std::vector<ErrorStats> reference_by_body;  // the same per body, indexed like Scene::bodies
  // Law part and residual of that divergence: over the whole run in free flight; with contacts,
  // over the free fall before either run (or law) first touches a floor (the laws know no
  // contacts).
  std::optional<Attribution> attribution;
  double attributed_until = -1.0;  // s: contacts: last sample time the attribution covers; -1 all
  std::vector<LandingResult> landings;  // contact scenes: one per body above a floor
  std::optional<Timing> timing;

  // Error against the continuous reference (oracle 1, else oracle 3): max |dx| in m; NaN if none.
  double continuous_error() const;
  // The same error's ErrorStats, or nullptr when there is no continuous reference.
  const ErrorStats* continuous() const;
};

// One engine over the whole sweep.
struct EngineEvaluation {
  std::string name;
  std::string skipped;                    // why the engine did not run the scene; empty when it ran
  EngineInfo info;                        // filled when the engine is available
  std::vector<StepEvaluation> sweep;      // parallel to SceneEvaluation::sweep
  std::size_t default_index = 0;          // entry of `sweep` at the scene's default step
  Trajectory fine;                        // oracle 3's run (empty when unused)
  std::vector<double> orders_continuous;  // observed orders of continuous_error() over the sweep
  std::vector<double> orders_reference;   // observed orders of the divergence from the reference
  std::string hash;                       // trajectory_hash_hex at the default step

  bool ran() const { return skipped.empty(); }
  const StepEvaluation& at_default() const { return sweep[default_index]; }
  // The first run of the sweep that did not finish (status != ok), or nullptr.
  const StepEvaluation* first_failure() const;
};

struct SceneEvaluation {
  // Copy-constructed from the scene, never assigned one: g++ 12 -O2 flags the assignment of the
  // forces' std::variant as maybe-uninitialized (a false positive -Werror would fail the build on).
  explicit SceneEvaluation(const Scene& s) : scene(s) {}

  Scene scene;
  std::vector<Timestep> sweep;  // the scene's steps, default included, largest first
  std::size_t default_index = 0;
  std::string no_analytic;     // analytic_unavailable(scene): why oracle 1 is absent
  bool uses_law = false;       // oracle 2 applies (no contacts)
  bool uses_fine = false;      // oracle 3 applies (no closed form)
  Timestep fine_step;          // oracle 3's step
  std::string reference;       // engine the divergences are measured from ("" when none ran)
  std::string reference_note;  // why it is not options.reference, when it is not
  std::optional<Trajectory> analytic;     // oracle 1 at the default step (for plots)
  std::vector<EngineEvaluation> engines;  // in the order given

  // The engine by name, or nullptr.
  const EngineEvaluation* find(const std::string& name) const;
};

// Progress lines ("bullet 1/120", "timing 1/60") for a person watching a long run.
using Progress = std::function<void(const std::string&)>;

// scene_sweep(scene) (harness/study/sweep.hpp): the one sweep every command measures over.
std::vector<Timestep> sorted_sweep(const Scene& scene);

// Runs every engine of `engines` that can run `scene` over the sweep and measures it.
SceneEvaluation evaluate_scene(const Scene& scene, const std::vector<EngineSlot>& engines,
                               const EvaluateOptions& options = {}, const Progress& progress = {});

// Times every engine at every step of every scene's sweep whose run there finished, as one schedule
// (time_engines, harness/timing/timing.hpp), and stores each figure in its StepEvaluation::timing.
// `engines` are the slots `scenes` were evaluated with, in the same order.
void time_evaluations(std::vector<SceneEvaluation>& scenes, const std::vector<EngineSlot>& engines,
                      const TimingOptions& options = {}, const Progress& progress = {});

}  // namespace dropcheck
