// make_baseline: runs one scene on one engine over its sweep and measures it against both oracles.
// (The text format lives in baseline_io.cpp.)
#include "harness/guard/baseline.hpp"

#include <cmath>

#include "harness/core/build_id.hpp"
#include "harness/core/trajectory_hash.hpp"
#include "harness/judge/metrics.hpp"
#include "harness/judge/own_law.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/oracles/analytic.hpp"
#include "harness/oracles/contact_laws.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/oracles/identify_rotation.hpp"
#include "harness/oracles/landing.hpp"
#include "harness/oracles/own_arithmetic.hpp"
#include "harness/oracles/stack.hpp"
#include "harness/run/runner.hpp"
#include "harness/study/sweep.hpp"
#include "harness/timing/timing.hpp"

namespace dropcheck {
namespace {

// Keeps step 0, every `every`-th step and the last sample of a trajectory recorded at every step.
Trajectory downsample(const Trajectory& full, std::int64_t every) {
  Trajectory t = full;
  t.recorded.clear();
  t.states.clear();
  t.rotations.clear();
  for (std::size_t s = 0; s < full.samples(); ++s) {
    if (full.recorded[s] % every != 0 && s + 1 != full.samples()) continue;
    t.recorded.push_back(full.recorded[s]);
    for (std::size_t b = 0; b < full.bodies(); ++b) {
      t.states.push_back(full.at(s, b));
      if (full.rotates) t.rotations.push_back(full.rotation_at(s, b));
    }
  }
  return t;
}

std::string status_text(const Trajectory& t) {
  std::string s = to_string(t.status);
  if (t.status != RunStatus::ok) s += ": " + t.failure;
  return s;
}

// Oracle 2: the engine's departure from its own discrete law, worst dynamic body, and the first
// step at which any body leaves the own-law tolerance.
void measure_law(const Scene& scene, const Trajectory& run, const Trajectory& law, double budget,
                 SweepPoint& p) {
  for (std::size_t b = 0; b < run.bodies(); ++b) {
    if (scene.bodies[b].is_static) continue;
    const ErrorStats e = compare(run, law, b, budget);
    if (p.law_worst_body.empty() || e.max_dx > p.law_max_dx) {
      p.law_max_dx = e.max_dx;
      p.law_worst_body = run.body_names[b];
    }
    if (e.diverged_at < 0.0) continue;
    const std::int64_t step = std::llround(e.diverged_at / run.h);
    if (p.law_first_over < 0 || step < p.law_first_over) p.law_first_over = step;
  }
}

// One point of the sweep: the run at dt (every step recorded) against both oracles.
SweepPoint measure(const Scene& scene, const EngineInfo& info, const Trajectory& run,
                   const Timestep& dt) {
  SweepPoint p;
  p.dt = dt;
  p.steps = run.steps;
  p.status = to_string(run.status);
  if (const auto exact = analytic_trajectory(scene, dt.seconds)) {
    const ErrorStats e = compare_worst(run, *exact, scene.tolerance);
    p.analytic_max_dx = e.max_dx;
    p.analytic_final_dx = e.final_dx;
  }
  const Trajectory own = predict_own_arithmetic(info, scene, dt.seconds);
  const OwnLawVerdict verdict =
      judge_own_law(info, run, own, predict_discrete(info.law, scene, dt.seconds));
  measure_law(scene, run, own, verdict.tolerance.x, p);
  if (scene.world.contacts) return p;  // the laws know no contacts: no verdict
  p.own_law = verdict;
  if (!verdict.follows()) p.fits = fitting_law(info, scene, run);
  if (!verdict.follows() && run.rotates && run.status == RunStatus::ok) {
    // The member that fits, or every member that ties with it (a steady spin hides the
    // gyroscopic term, not the orientation update).
    const RotationIdentification id = identify_rotation(scene, run);
    const double best = id.fits[id.best].max_angle;
    for (const RotationFit& f : id.fits)
      if (id.fits_any && f.max_angle <= 2.0 * best + 1e-12)
        p.rotation_fits += (p.rotation_fits.empty() ? "" : " or ") + rotation_law_key(f.law);
  }
  return p;
}

void add_timing(const Scene& scene, const EngineFactory& make, const std::string& name,
                SweepPoint& p) {
  const std::vector<Timing> t = time_engines({{name, make}}, scene, p.dt.seconds);
  p.wall_min = t.front().of(Statistic::min);
  p.wall_median = t.front().of(Statistic::median);
  p.replicas = t.front().replicas;
}

}  // namespace

Baseline make_baseline(const Scene& scene, const EngineFactory& make,
                       const BaselineOptions& options) {
  Baseline out;
  std::unique_ptr<Engine> engine = make();
  const EngineInfo info = engine->info();
  out.provenance = provenance("unknown commit");
  out.build_keys = {current_build().key};
  out.scene = scene.name;
  out.engine = info.name;
  out.scalar = info.scalar;
  out.law = to_string(info.law);
  const std::string no_oracle = analytic_unavailable(scene);
  out.analytic = no_oracle.empty() ? "closed form" : "none: " + no_oracle;
  out.dt = scene.timestep;
  out.record_every = options.record_every < 1 ? 1 : options.record_every;
  out.skipped = engine->cannot_run(scene);
  if (!out.skipped.empty()) return out;

  // What the baseline keeps of the run at the scene's own step.
  const auto keep = [&](const Trajectory& run) {
    out.status = status_text(run);
    out.hash = trajectory_hash_hex(run);
    out.samples = downsample(run, out.record_every);
    out.contact = contact_figures(scene, run);
  };
  bool default_in_sweep = false;
  for (const Timestep& dt : scene_sweep(scene)) {
    const Trajectory run = run_scene(*make(), scene, dt.seconds);
    out.sweep.push_back(measure(scene, info, run, dt));
    if (options.timing) add_timing(scene, make, info.name, out.sweep.back());
    if (!same_step(dt.seconds, scene.timestep.seconds)) continue;
    default_in_sweep = true;
    keep(run);
  }
  if (!default_in_sweep) keep(run_scene(*make(), scene, scene.timestep.seconds));
  return out;
}

std::vector<ContactFigure> contact_figures(const Scene& scene, const Trajectory& run) {
  std::vector<ContactFigure> out;
  if (!scene.world.contacts || !run.keeps_every_step()) return out;
  // A run that blew up has no finite distance or apex to keep.
  const auto add = [&](const std::string& name, double value) {
    if (std::isfinite(value) && out.size() < kMaxContactFigures) out.push_back({name, value});
  };
  std::vector<char> judged(scene.bodies.size(), 0);  // by a slide or a bounce
  for (const SlideSetup& s : slide_setups(scene)) {
    judged[s.body] = 1;
    const SlideObservation o = observe_slide(observed_slide_path(run, s), tolerance::kStoppedSpeed,
                                             tolerance::kSlideDistance);
    const std::string& body = scene.bodies[s.body].name;
    add(body + ".stop_step", static_cast<double>(o.stop_step));
    add(body + ".distance", o.distance);
  }
  for (const BounceSetup& s : bounce_setups(scene)) {
    judged[s.body] = 1;
    const BouncePath path = observed_path(run, s);
    const BounceObservation o = observe_bounce(path.gap, path.v, s.g, run.h);
    const std::string& body = scene.bodies[s.body].name;
    add(body + ".contact_step", static_cast<double>(o.contact_step));
    for (std::size_t i = 0; i < o.apexes.size(); ++i)
      add(body + ".apex_" + std::to_string(i + 1), o.apexes[i]);
  }
  if (run.samples() == 0) return out;  // a run that never started has no final state
  for (const LandingExclusion& x : landing_exclusions(scene)) judged[x.body] = 1;
  for (const LandingSetup& s : landing_setups(scene)) {
    if (judged[s.body]) continue;
    const std::string& body = scene.bodies[s.body].name;
    add(body + ".first_contact_step", static_cast<double>(first_contact_step(run, s)));
    add(body + ".rest_offset", run.final_state(s.body).position.y() - s.rest_height);
  }
  for (const StackSetup& s : stack_setups(scene))
    for (const StackLevel& l : s.levels)
      add(scene.bodies[l.body].name + ".sink",
          l.rest_height - run.final_state(l.body).position.y());
  return out;
}

std::string provenance(const std::string& commit) {
  const BuildId id = current_build();
  return "made by `dropcheck bless` with " + id.key + ", build type " +
         (id.build_type.empty() ? "(none)" : id.build_type) + " \"" + id.flags + "\", on commit " +
         commit;
}

std::string baseline_file_name(const std::string& scene, const std::string& engine) {
  return scene + "." + engine + ".txt";
}

}  // namespace dropcheck
