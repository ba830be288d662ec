#include "harness/study/identify_analysis.hpp"

#include "harness/core/law.hpp"
#include "harness/core/scene.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/oracles/contact_laws.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {

std::optional<RunFailure> run_failure(const Trajectory& run, const std::string& engine) {
  if (run.status == RunStatus::ok) return std::nullopt;
  return RunFailure{engine, run.failed_step, run.status, run.failure};
}

namespace {

// The declared linear member against the fits: named, or one of two equal fits.
DeclaredMatch law_match(const Identification& id, bool named, Law declared) {
  if (named && id.fits[id.best].law == declared) return DeclaredMatch::matches;
  for (std::size_t i : id.tied)
    if (id.ambiguous && id.fits[i].law == declared) return DeclaredMatch::tied;
  return DeclaredMatch::mismatch;
}

// Whether every order measured is the declared law's.
bool orders_match(const ClosedFormOrder& o, Law declared) {
  if (!o.unavailable.empty()) return true;
  bool match = true;
  for (double p : o.estimate.orders) match = match && order_matches(p, order_of(declared));
  return match;
}

// The declared rotational member against the fits: its member and position update, and, when
// the scene's angular damping shows it, its damping placement.
RotationDeclared rotation_declared(const RotationIdentification& id, bool named,
                                   const EngineInfo& info) {
  RotationDeclared d{{info.rotation_law, info.law}, DeclaredMatch::mismatch};
  const RotationFit& want = d.member;
  const auto same = [&](const RotationFit& f) {
    return f.law == want.law && f.linear.position == want.linear.position &&
           (!id.damping_seen || law_difference(f.linear, want.linear).empty());
  };
  const RotationFit& best = id.fits[id.best];
  bool tied = false;  // the declared member fits as well as the best (within the 2x of ambiguity)
  for (const RotationFit& f : id.fits)
    tied = tied || (same(f) && f.max_angle <= 2.0 * best.max_angle + 1e-12);
  d.match = named && same(best)    ? DeclaredMatch::matches
            : id.ambiguous && tied ? DeclaredMatch::tied
                                   : DeclaredMatch::mismatch;
  return d;
}

// The law behind `run`; with `declared` (the engine's info) and `engine`, against its declaration.
FreeFlightIdentity free_flight(const Scene& scene, const Trajectory& run,
                               const EngineInfo* declared, Engine* engine) {
  FreeFlightIdentity f;
  f.scene = scene.name;
  f.engine = run.engine;
  f.bodies = run.bodies();
  f.steps = run.steps;
  f.h = run.h;
  f.law = identify_law(scene, run);
  if (declared) {
    f.declared = declared->law;
    f.law_match = law_match(f.law, f.named(), declared->law);
    f.order = order_against_closed_form(*engine, scene, run.h);
    f.order_matches = orders_match(*f.order, declared->law);
  }
  if (run.rotates) {
    f.rotation = identify_rotation(scene, run);
    if (declared)
      f.rotation_declared = rotation_declared(*f.rotation, f.rotation_named(), *declared);
  } else {
    f.rotation_unread = needs_rotation(scene);
  }
  return f;
}

}  // namespace

bool FreeFlightIdentity::named() const {
  return law.fits_any && !law.ambiguous && law.determined;
}

bool FreeFlightIdentity::rotation_named() const {
  return rotation && rotation->fits_any && !rotation->ambiguous;
}

bool FreeFlightIdentity::ok() const {
  bool ok = named();
  if (declared) ok = ok && law_match == DeclaredMatch::matches && order_matches;
  if (rotation)
    ok = ok && (rotation_declared ? rotation_declared->match == DeclaredMatch::matches
                                  : rotation_named());
  return ok;
}

FreeFlightIdentity identify_free_flight(const Scene& scene, const Trajectory& run, Engine* engine) {
  if (!engine) return free_flight(scene, run, nullptr, nullptr);
  const EngineInfo info = engine->info();
  return free_flight(scene, run, &info, engine);
}

bool EngineIdentity::ok() const {
  if (accuracy) return accuracy->within();
  return !failed && fit && fit->ok();
}

EngineIdentity identify_engine(const Scene& scene, Engine& engine, double h) {
  EngineIdentity e;
  e.scene = scene.name;
  e.info = engine.info();
  e.h = h;
  if (e.info.law.scheme == Scheme::ErrorControlled) {
    e.accuracy = error_per_accuracy(engine, scene, h);
    return e;
  }
  const Trajectory run = run_scene(engine, scene, h);
  e.failed = run_failure(run, run.engine);
  if (!e.failed) e.fit = free_flight(scene, run, &e.info, &engine);
  return e;
}

bool FrictionModelIdentity::ok() const {
  if (planar) return true;
  if (failed || !found) return false;
  if (raw) return found->named.has_value();
  // A slide that cannot tell some models apart is consistent with any of them.
  for (const FrictionModelFit& fit : found->fits)
    if (fit.model == declared && fit.fits) return true;
  return false;
}

namespace {

// One slide of the pair, run to its stop: its distance, or nullopt when `f` says why not (the run
// failed, or it still slides at the run's end). `angle`: 0 or 45 degrees.
std::optional<double> slide_distance(const Scene& s, int angle, const IdentifySource& source,
                                     FrictionModelIdentity& f, double& h) {
  FrictionEngine fe = source.friction_engine(s);
  f.engine = fe.engine->info().name;
  f.declared = fe.engine->info().friction_model;
  f.raw = fe.raw;
  h = source.step(s);
  const Trajectory run = run_scene(*fe.engine, s, h);
  if ((f.failed = run_failure(run, run.engine))) return std::nullopt;
  // The distance to the stop, or to the run's end for an engine that creeps on (Bullet ends at
  // 9e-5 m/s); a slide still above 1 % of its launch speed at the end has no distance yet. A
  // slide pulled along its floor: the distance at the run's end.
  const SlideSetup slide = slide_setups(s).at(0);
  const SlidePath path = observed_slide_path(run, slide);
  if (slide.pull != 0.0) {
    if (fe.raw && angle == 0) f.mu = pair_friction(s, run);
    return path.s.back();
  }
  const SlideObservation seen =
      observe_slide(path, tolerance::kStoppedSpeed, tolerance::kSlideDistance);
  // Still sliding is judged on the speed alone: a creep below 1 % of the launch speed is a stop.
  if (observe_slide(path, 0.01 * slide.v0, std::numeric_limits<double>::infinity()).stop_step < 0) {
    f.engine = run.engine;
    f.still_sliding_angle = angle;
    f.still_sliding_distance = seen.distance;
    return std::nullopt;
  }
  if (fe.raw && angle == 0) f.mu = pair_friction(s, run);
  return seen.distance;
}

}  // namespace

FrictionModelIdentity identify_friction_model(const Scene& scene, const IdentifySource& source) {
  FrictionModelIdentity f;
  f.scene = scene.name;
  const SlidePair pair = slide_pair(scene);
  if (const std::optional<EngineInfo> named = source.named_info();
      named && named->capabilities.planar_only) {
    f.planar = true;
    f.engine = named->name;
    return f;
  }
  double h = 0.0;
  const std::optional<double> along = slide_distance(pair.along_axis, 0, source, f, h);
  if (!along) return f;
  const std::optional<double> diagonal = slide_distance(pair.diagonal, 45, source, f, h);
  if (!diagonal) return f;
  f.found = identify_friction(scene, h, *along, *diagonal, f.mu);
  return f;
}

bool CombineRuleIdentity::ok() const {
  return per_pair || (!failed && found && found->named);
}

CombineRuleIdentity identify_combine_rule(const Scene& scene, Engine& engine,
                                          const IdentifySource& source) {
  CombineRuleIdentity c;
  c.engine = engine.info().name;
  if (!engine.use_body_materials()) {
    c.per_pair = true;
    return c;
  }
  const Scene combined = combine_scene(scene);
  const Trajectory run = run_scene(engine, combined, source.step(combined));
  if ((c.failed = run_failure(run, c.engine))) return c;
  c.found = identify_combine(combined, run);
  return c;
}

}  // namespace dropcheck
