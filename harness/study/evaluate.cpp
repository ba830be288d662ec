#include "harness/study/evaluate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "harness/core/number_format.hpp"
#include "harness/core/timestep.hpp"
#include "harness/core/trajectory_hash.hpp"
#include "harness/judge/own_law.hpp"
#include "harness/oracles/analytic.hpp"
#include "harness/oracles/contact_closed_form.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/oracles/own_arithmetic.hpp"
#include "harness/process/stderr_capture.hpp"
#include "harness/run/runner.hpp"
#include "harness/study/sweep.hpp"

namespace dropcheck {
namespace {

constexpr double kNoFigure = std::numeric_limits<double>::quiet_NaN();

void say(const Progress& progress, const std::string& what) {
  if (progress) progress(what);
}

// The references every engine shares at each step of the sweep, computed once.
class References {
 public:
  References(const Scene& scene, const std::vector<Timestep>& sweep)
      : scene_(scene), sweep_(sweep) {
    for (const Timestep& h : sweep) analytic_.push_back(closed_form_trajectory(scene, h.seconds));
  }
  // Oracle 1 at sweep step i (nullopt without a closed form).
  const std::optional<Trajectory>& analytic(std::size_t i) const { return analytic_[i]; }
  // Oracle 2 for `law` at sweep step i, predicted on first use.
  const Trajectory& law(Law law, std::size_t i) {
    auto key = std::make_pair(law_key(law), i);
    auto it = laws_.find(key);
    if (it == laws_.end())
      it = laws_.emplace(key, predict_discrete(law, scene_, sweep_[i].seconds)).first;
    return it->second;
  }
  // Oracle 2 in the engine's own arithmetic at sweep step i, predicted on first use. An engine
  // whose arithmetic is not copied shares the long-double law, unless the scene turns its bodies:
  // its rotational member is its own (predict_own_arithmetic adds it).
  const Trajectory& own(const EngineInfo& info, std::size_t i) {
    const bool turns = needs_rotation(scene_) && info.capabilities.rotation != Rotation::none;
    if (!arithmetic_copied(info) && !turns) return law(info.law, i);
    auto key = std::make_pair(info.name, i);
    auto it = own_.find(key);
    if (it == own_.end())
      it = own_.emplace(key, predict_own_arithmetic(info, scene_, sweep_[i].seconds)).first;
    return it->second;
  }

 private:
  const Scene& scene_;
  const std::vector<Timestep>& sweep_;
  std::vector<std::optional<Trajectory>> analytic_;
  std::map<std::pair<std::string, std::size_t>, Trajectory> laws_, own_;
};

// Oracle 3's step: the finest step of the sweep divided by `factor` (halved until it divides the
// duration into whole steps). Written "1/(N*factor)" when the finest step is "1/N".
std::optional<Timestep> fine_step(const Scene& scene, const Timestep& finest, int factor) {
  for (; factor >= 2; factor /= 2) {
    const double h = finest.seconds / factor;
    if (!step_problem(scene.duration, h).empty()) continue;
    return Timestep{h, divided_step_text(finest.text, finest.seconds, factor)};
  }
  return std::nullopt;
}

EngineEvaluation open_engine(const Scene& scene, const EngineSlot& slot) {
  EngineEvaluation ev;
  ev.name = slot.name;
  if (!slot.make) {
    ev.skipped = slot.unavailable.empty() ? "not available" : slot.unavailable;
    return ev;
  }
  std::unique_ptr<Engine> engine = slot.make();
  if (!engine) {
    ev.skipped = "its factory made no engine";
    return ev;
  }
  ev.info = engine->info();
  ev.skipped = engine->cannot_run(scene);
  return ev;
}

// Runs one engine over the sweep and measures each run against oracles 1 and 2.
void run_sweep(EngineEvaluation& ev, const EngineSlot& slot, const SceneEvaluation& se,
               References& refs, const Progress& progress) {
  const double tol = se.scene.tolerance;
  for (std::size_t i = 0; i < se.sweep.size(); ++i) {
    say(progress, ev.name + " " + se.sweep[i].text);
    StepEvaluation s;
    s.h = se.sweep[i];
    s.run = run_scene(*slot.make(), se.scene, s.h.seconds);
    if (refs.analytic(i)) s.vs_analytic = compare_worst(s.run, *refs.analytic(i), tol);
    if (se.uses_law) {
      const Trajectory& own = refs.own(ev.info, i);
      s.vs_law = compare_worst(s.run, own, tol);
      s.own_law = judge_own_law(ev.info, s.run, own, refs.law(ev.info.law, i));
      s.law_budget = s.own_law->tolerance.x;
    }
    ev.sweep.push_back(std::move(s));
  }
  ev.default_index = se.default_index;
  ev.hash = trajectory_hash_hex(ev.at_default().run);
}

// Oracle 3: the same engine at the fine step, compared at the sweep runs' sample times.
void run_fine(EngineEvaluation& ev, const EngineSlot& slot, const SceneEvaluation& se,
              const Progress& progress) {
  say(progress, ev.name + " " + se.fine_step.text + " (fine-step reference)");
  ev.fine = run_scene(*slot.make(), se.scene, se.fine_step.seconds);
  for (StepEvaluation& s : ev.sweep) s.vs_fine = compare_worst(s.run, ev.fine, se.scene.tolerance);
}

// Landing figures of every run of a contact scene (harness/oracles/landing.hpp). An engine whose
// resting surface sits above the geometry (Box2D's 0.01 m skin) touches the floor there: contact
// means reaching floor top + rest_offset (+ its tolerance), as `dropcheck check` counts it.
void measure_landings(EngineEvaluation& ev, const SceneEvaluation& se) {
  const std::vector<LandingSetup> setups = engine_landing_setups(se.scene, ev.info);
  for (StepEvaluation& s : ev.sweep) {
    for (const LandingSetup& setup : setups) {
      LandingResult r{setup, observe_landing(s.run, setup), kNoFigure, {}, {}};
      const std::int64_t n = discrete_contact_step(ev.info.law, se.scene, s.h.seconds, setup);
      if (n >= 0) r.law_contact_time = static_cast<double>(n) * s.h.seconds;
      r.expected = landing_expectation(ev.info, se.scene, s.h.seconds, setup);
      r.end = judge_landing_end(s.run, setup, r.seen, r.expected, ev.info);
      s.landings.push_back(r);
    }
  }
}

// The engine divergences are measured from: the requested one if it ran, else the first that ran.
void choose_reference(SceneEvaluation& se, const std::string& wanted) {
  const EngineEvaluation* w = se.find(wanted);
  if (w && w->ran()) {
    se.reference = wanted;
    return;
  }
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran()) continue;
    se.reference = ev.name;
    se.reference_note =
        wanted + " did not run this scene (" + (w ? w->skipped : "not listed") + ")";
    return;
  }
}

// The step before the first one on which any of the trajectories has a body at or below its
// floor (harness/oracles/landing.hpp): until then every body is in free flight. -1 when none lands.
// A turning box may touch with a corner as soon as its centre is within its half-diagonal of the
// floor: that is the height counted for it.
std::int64_t free_flight_end(const Scene& scene, std::initializer_list<const Trajectory*> runs) {
  std::int64_t first = -1;
  for (LandingSetup setup : landing_setups(scene)) {
    if (needs_rotation(scene)) setup.half_height = scene.bodies[setup.body].half_extents.norm();
    for (const Trajectory* t : runs)
      if (const std::int64_t n = first_contact_step(*t, setup); n >= 0 && (first < 0 || n < first))
        first = n;
  }
  // One step earlier: an engine with a contact skin (Box2D, 0.01 m) meets the floor up to one
  // step before its bottom does.
  return first < 0 ? -1 : std::max<std::int64_t>(first - 1, 0);
}

// Divergence of `ev` from the reference at every step, and its attribution (law part, residual)
// over the free flight: the whole run without contacts, the fall before landing with contacts.
void measure_divergence(EngineEvaluation& ev, const EngineEvaluation& ref,
                        const SceneEvaluation& se, References& refs) {
  const bool damped = se.scene.world.damping_rate != 0.0;
  for (std::size_t i = 0; i < ev.sweep.size(); ++i) {
    StepEvaluation& s = ev.sweep[i];
    const Trajectory& r = ref.sweep[i].run;
    for (std::size_t b = 0; b < s.run.bodies(); ++b)
      s.reference_by_body.push_back(compare(s.run, r, b, se.scene.tolerance));
    s.vs_reference = compare_worst(s.run, r, se.scene.tolerance);
    const Trajectory& le = refs.law(ev.info.law, i);
    const Trajectory& lr = refs.law(ref.info.law, i);
    const Trajectory& ae = refs.own(ev.info, i);
    const Trajectory& ar = refs.own(ref.info, i);
    if (se.uses_law) {
      s.attribution = attribute({ev.info, s.run, ae, le}, {ref.info, r, ar, lr}, damped);
      continue;
    }
    const std::int64_t n = free_flight_end(se.scene, {&s.run, &r, &le, &lr});
    if (n <= 0) continue;
    const Trajectory es = before_step(s.run, n), rs = before_step(r, n);
    const Trajectory aes = before_step(ae, n), ars = before_step(ar, n);
    const Trajectory les = before_step(le, n), lrs = before_step(lr, n);
    s.attribution = attribute({ev.info, es, aes, les}, {ref.info, rs, ars, lrs}, damped);
    s.attributed_until = s.attribution->final_t;
  }
}

// Observed orders p = ln(e1/e2)/ln(h1/h2) of the continuous error and of the divergence. A
// divergence within the two engines' rounding budget counts as zero: the order of noise means
// nothing.
void measure_orders(EngineEvaluation& ev, const SceneEvaluation& se) {
  std::vector<double> h, cont, div;
  for (const StepEvaluation& s : ev.sweep) {
    h.push_back(s.h.seconds);
    cont.push_back(s.continuous_error());
    const double budget = s.attribution ? s.attribution->budget : 0.0;
    const double d = s.vs_reference ? s.vs_reference->max_dx : kNoFigure;
    div.push_back(d <= budget ? 0.0 : d);
  }
  if (se.uses_fine || se.no_analytic.empty()) ev.orders_continuous = observed_orders(h, cont);
  if (ev.name != se.reference) ev.orders_reference = observed_orders(h, div);
}

SceneEvaluation prepare(const Scene& scene, const EvaluateOptions& options) {
  SceneEvaluation se(scene);
  se.sweep = sorted_sweep(scene);
  se.default_index = default_index(se.sweep, scene);
  se.no_analytic = closed_form_unavailable(scene);
  se.uses_law = !scene.world.contacts;
  if (!se.no_analytic.empty()) {
    const std::optional<Timestep> fine = fine_step(scene, se.sweep.back(), options.fine_factor);
    se.uses_fine = fine.has_value();
    if (fine) se.fine_step = *fine;
  }
  se.analytic = closed_form_trajectory(scene, scene.timestep.seconds);
  return se;
}

}  // namespace

double StepEvaluation::continuous_error() const {
  const ErrorStats* c = continuous();
  return c ? c->max_dx : kNoFigure;
}

const ErrorStats* StepEvaluation::continuous() const {
  if (vs_analytic) return &*vs_analytic;
  if (vs_fine) return &*vs_fine;
  return nullptr;
}

const StepEvaluation* EngineEvaluation::first_failure() const {
  for (const StepEvaluation& s : sweep)
    if (s.run.status != RunStatus::ok) return &s;
  return nullptr;
}

const EngineEvaluation* SceneEvaluation::find(const std::string& name) const {
  for (const EngineEvaluation& ev : engines)
    if (ev.name == name) return &ev;
  return nullptr;
}

std::vector<Timestep> sorted_sweep(const Scene& scene) {
  return scene_sweep(scene);
}

SceneEvaluation evaluate_scene(const Scene& scene, const std::vector<EngineSlot>& engines,
                               const EvaluateOptions& options, const Progress& progress) {
  SceneEvaluation se = prepare(scene, options);
  References refs(se.scene, se.sweep);
  for (std::size_t e = 0; e < engines.size(); ++e) {
    se.engines.push_back(open_engine(scene, engines[e]));
    EngineEvaluation& ev = se.engines.back();
    if (!ev.ran()) continue;
    run_sweep(ev, engines[e], se, refs, progress);
    if (se.uses_fine) run_fine(ev, engines[e], se, progress);
    // A turning body's landing has no closed form (check_landing says so): not measured.
    if (scene.world.contacts && !needs_rotation(scene)) measure_landings(ev, se);
  }
  choose_reference(se, options.reference);
  const EngineEvaluation* ref = se.find(se.reference);
  for (EngineEvaluation& ev : se.engines) {
    if (!ev.ran()) continue;
    if (ref && ev.name != ref->name) measure_divergence(ev, *ref, se, refs);
    measure_orders(ev, se);
  }
  return se;
}

void time_evaluations(std::vector<SceneEvaluation>& scenes, const std::vector<EngineSlot>& engines,
                      const TimingOptions& options, const Progress& progress) {
  // One cell per scene and step of its sweep: every engine whose run at that step finished, timed
  // cell after cell, each through all its rounds back to back. Measured: going round all the cells
  // instead (every round visiting every cell) let two back-to-back reports agree within 10 % on
  // only 44 % of the cells on a quiet machine (the halves of one report: median difference 14.5 %),
  // against 93-100 % cell after cell: between two samples of a cell every other cell ran, and its
  // engines met the caches, heap and clock in another state each time.
  std::size_t cells = 0, c = 0;
  std::map<std::string, std::int64_t> total;  // what the engines printed, counted over all cells
  for (const SceneEvaluation& se : scenes) cells += se.sweep.size();
  for (SceneEvaluation& se : scenes)
    for (std::size_t i = 0; i < se.sweep.size(); ++i) {
      say(progress, "timing cell " + std::to_string(++c) + " of " + std::to_string(cells));
      std::vector<std::pair<std::string, EngineFactory>> cell;
      std::vector<StepEvaluation*> targets;
      for (std::size_t e = 0; e < se.engines.size(); ++e) {
        EngineEvaluation& ev = se.engines[e];
        if (!ev.ran() || ev.sweep[i].run.status != RunStatus::ok) continue;
        cell.emplace_back(ev.name, engines[e].make);
        targets.push_back(&ev.sweep[i]);
      }
      // The engines run in this process while timed: what they print is counted, not shown.
      StderrCapture printed;
      const std::vector<Timing> t = time_engines(cell, se.scene, se.sweep[i].seconds, options);
      const CountedLines lines = printed.finish();
      for (const Trajectory::Message& m : lines.messages()) total[m.text] += m.count;
      for (std::size_t k = 0; k < t.size(); ++k) targets[k]->timing = t[k];
    }
  // One line per distinct message over the whole timing, not one per cell: an engine that
  // complains in every cell would flood the terminal again.
  for (const auto& [text, count] : total)
    say(progress, "timing: '" + text + "' printed " + std::to_string(count) +
                      " times over the timing cells (kept from the terminal)");
}

}  // namespace dropcheck
