// The stability study of one scene: run at the scene's step, classify, compare with the analytic
// oracle, search the largest stable step, and the spring theory of each engine's damping order.
#include "harness/study/stability_study.hpp"

#include <cmath>

#include "harness/core/number_format.hpp"
#include "harness/judge/stability_contact.hpp"
#include "harness/oracles/analytic.hpp"
#include "harness/oracles/stability_theory.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {
namespace {

// Runs `engine` at the scene's own step and classifies the run.
void study_default_step(Engine& engine, const Scene& scene, const StudyOptions& o,
                        EngineStability& r) {
  const double h = scene.timestep.seconds;
  RunOptions run_options;
  run_options.record_every = stability_record_every(scene, h);
  const Trajectory run = run_scene(engine, scene, h, run_options);
  r.status = run.status;
  r.steps_run = run.recorded.empty() ? 0 : run.recorded.back();
  r.verdict = classify_engine_run(scene, run, engine.info(), o.classify);
  if (std::optional<Trajectory> exact = analytic_trajectory(scene, h, run_options))
    r.vs_analytic = compare_worst(run, *exact, scene.tolerance);
}

EngineStability study_engine(const EngineSlot& slot, const Scene& scene, const StudyOptions& o) {
  EngineStability r;
  r.engine = slot.name;
  std::unique_ptr<Engine> engine = slot.make ? slot.make() : nullptr;
  if (!engine) {
    r.skipped = slot.unavailable.empty() ? "not available" : slot.unavailable;
    return r;
  }
  const EngineInfo info = engine->info();
  r.engine = info.name;  // an engine file's engine is shown under its own name
  r.scalar = info.scalar;
  r.law = info.law;
  if (std::string why = engine->cannot_run(scene); !why.empty()) {
    r.skipped = why;
    return r;
  }
  study_default_step(*engine, scene, o, r);
  r.theory_max_dt = theory_max_dt(scene, r.law);
  if (o.search) {
    r.search = search_max_stable_dt(slot.make, scene, scene.timestep.seconds, o.search_options,
                                    o.classify);
  }
  return r;
}

std::string progress_line(const SceneStability& s, const EngineStability& e) {
  if (!e.ran())
    return printf_string("stability %s: %s skipped (%s)\n", s.name.c_str(), e.engine.c_str(),
                         e.skipped.c_str());
  const std::string verdict =
      e.verdict.stable() ? std::string("stable") : to_string(e.verdict.failures.front().mode);
  const std::string probes =
      e.search ? printf_string(", %d probes", e.search->probes) : std::string();
  return printf_string("stability %s: %s %s%s\n", s.name.c_str(), e.label().c_str(),
                       verdict.c_str(), probes.c_str());
}

}  // namespace

SceneStability study_scene(const Scene& scene, const std::vector<EngineSlot>& engines,
                           const StudyOptions& options, std::ostream* progress) {
  SceneStability s;
  s.name = scene.name;
  s.source = scene.source;
  s.description = scene.description;
  s.h = scene.timestep;
  s.duration = scene.duration;
  s.steps = step_count(scene, scene.timestep.seconds);
  s.no_analytic = analytic_unavailable(scene);
  for (const EngineSlot& slot : engines) {
    s.engines.push_back(study_engine(slot, scene, options));
    if (progress) *progress << progress_line(s, s.engines.back()) << std::flush;
  }
  return s;
}

}  // namespace dropcheck
