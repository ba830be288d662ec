#include "harness/study/divergence.hpp"

#include <algorithm>
#include <memory>

#include "harness/judge/law_stability.hpp"
#include "harness/judge/metrics.hpp"
#include "harness/oracles/analytic.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/oracles/own_arithmetic.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {

bool DivergenceStep::measured() const {
  return unstable.empty() && failure.empty();
}

std::vector<double> Divergence::measured_h() const {
  std::vector<double> out;
  for (const DivergenceStep& s : steps)
    if (s.measured()) out.push_back(s.h.seconds);
  return out;
}

std::vector<double> Divergence::measured_errors() const {
  std::vector<double> out;
  for (const DivergenceStep& s : steps)
    if (s.measured()) out.push_back(s.error);
  return out;
}

const DivergenceStep* Divergence::first_left_out() const {
  for (const DivergenceStep& s : steps)
    if (!s.unstable.empty()) return &s;
  return nullptr;
}

const DivergenceStep* Divergence::first_departure() const {
  for (const DivergenceStep& s : steps)
    if (s.own && !s.own->follows()) return &s;
  return nullptr;
}

const DivergenceStep* Divergence::rotations_apart() const {
  for (const DivergenceStep& s : steps)
    if (const std::optional<Attribution>& a = s.attribution;
        a && (a->rotation_laws_differ() ||
              (a->rotation && !a->rotation_laws_differ() && a->rotation_total > 0.0)))
      return &s;
  return nullptr;
}

bool Divergence::limit() const {
  return finding == DivergenceFinding::phase_drift && drift->explained;
}

namespace {

// A run of an extended sweep keeps at most this many samples (a long scene halved twice has
// millions of steps; 200000 samples of two bodies take 19 MB).
constexpr std::int64_t kExtensionSamples = 200000;

RunOptions extension_options(const Scene& scene, double h) {
  RunOptions o;
  o.record_every = std::max<std::int64_t>(1, step_count(scene, h) / kExtensionSamples);
  return o;
}

// The error of the next step of a pre-asymptotic sweep. The reference: its run against the
// analytic solution, provided it follows its own law there too (its precision part, own
// arithmetic against the long-double law, raises `precision`). Another engine: the law part
// |L_E - L_R| alone (both engines were shown to follow their laws over the scene's sweep; the law
// part is a property of the two laws).
ErrorAt extension_error(const Scene& scene, Engine& engine, const EngineInfo& ei,
                        const EngineInfo& ri, bool is_reference, double& precision) {
  return [&scene, &engine, &ei, &ri, is_reference, &precision](
             double h, std::string& why) -> std::optional<double> {
    const Timestep step{h, step_text(h)};
    for (const EngineInfo* i : {&ei, &ri})
      if (std::string u = law_instability(scene, i->law, step); !u.empty()) {
        why = i->name + ": " + u;
        return std::nullopt;
      }
    const RunOptions o = extension_options(scene, h);
    if (!is_reference)
      return compare_worst(predict_discrete(ei.law, scene, h, o),
                           predict_discrete(ri.law, scene, h, o), scene.tolerance)
          .max_dx;
    const Trajectory run = run_scene(engine, scene, h, o);
    if (run.status != RunStatus::ok) {
      why = "run failed: " + run.failure;
      return std::nullopt;
    }
    const Trajectory own = predict_own_arithmetic(ei, scene, h, o);
    const OwnLawVerdict v = judge_own_law(ei, run, own, predict_discrete(ei.law, scene, h, o));
    if (!v.follows()) {
      why = ei.name + " departs from its own law: " + v.sentence();
      return std::nullopt;
    }
    precision = std::max(precision, v.precision);
    return compare_worst(run, *analytic_trajectory(scene, h, o), scene.tolerance).max_dx;
  };
}

// The two engines of the check, each with its declared law.
struct Pair {
  const Scene& scene;
  Engine &engine, &ref;
  const EngineInfo &ei, &ri;
  bool to_analytic;
};

// Marks the step left out when either law is unstable at it. Each law's instability is asked
// once (RK4's predicts its rotation over the whole run to find it), the engine's first.
bool divergence_left_out(const Pair& p, DivergenceStep& s) {
  const std::string engine_unstable = law_instability(p.scene, p.ei.law, s.h);
  s.unstable = !engine_unstable.empty() || p.to_analytic ? engine_unstable
                                                         : law_instability(p.scene, p.ri.law, s.h);
  s.unstable_engine = s.unstable.empty() ? "" : engine_unstable.empty() ? p.ri.name : p.ei.name;
  return !s.unstable.empty();
}

// The reference's run at h against the closed form, and against its own law.
void measure_to_analytic(const Pair& p, const Trajectory& run, DivergenceStep& s) {
  const double h = s.h.seconds;
  const Trajectory ae = predict_own_arithmetic(p.ei, p.scene, h);
  const Trajectory le = predict_discrete(p.ei.law, p.scene, h);
  s.error = compare_worst(run, *analytic_trajectory(p.scene, h), p.scene.tolerance).max_dx;
  s.own_tolerance = own_law_tolerance(p.ei, ae).x;
  s.own = judge_own_law(p.ei, run, ae, le);
}

// The engine's run at h against the reference's: the difference split into its causes.
void measure_between(const Pair& p, const Trajectory& run, DivergenceStep& s) {
  const double h = s.h.seconds;
  const Trajectory ae = predict_own_arithmetic(p.ei, p.scene, h);
  const Trajectory le = predict_discrete(p.ei.law, p.scene, h);
  const Trajectory other = run_scene(p.ref, p.scene, h);
  const Trajectory ar = predict_own_arithmetic(p.ri, p.scene, h);
  const Trajectory lr = predict_discrete(p.ri.law, p.scene, h);
  s.attribution =
      attribute({p.ei, run, ae, le}, {p.ri, other, ar, lr}, p.scene.world.damping_rate != 0.0);
  const Attribution& a = *s.attribution;
  s.error = a.law_part > tolerance::kLawsDifferFactor * a.budget ? a.law_part : 0.0;
}

// One step of the sweep; false when the sweep stops at it (a failed run, an unexplained residual).
bool measure_step(const Pair& p, const Timestep& h, std::vector<DivergenceStep>& steps) {
  DivergenceStep& s = steps.emplace_back();
  s.h = h;
  if (divergence_left_out(p, s)) return true;
  const Trajectory run = run_scene(p.engine, p.scene, h.seconds);
  if (run.status != RunStatus::ok) {
    s.failure = run.failure;
    return false;
  }
  if (p.to_analytic) {
    measure_to_analytic(p, run, s);
    return true;
  }
  measure_between(p, run, s);
  return s.attribution->explained();
}

// The reference's noise floor and precision part over the scene's sweep.
void gather_rounding(Divergence& d) {
  double tolerance = 0.0;
  for (const DivergenceStep& s : d.steps) {
    tolerance = std::max(tolerance, s.own_tolerance);
    if (s.own) d.precision = std::max(d.precision, s.own->precision);
  }
  d.noise = tolerance::kOrderMeasurableFactor * tolerance;
}

// Out of band on a long run, the reference's extension out of reach: the phase drift of its law
// (phase_drift.hpp) may keep the error second order down to steps the cap does not allow.
void judge_phase_drift(const Pair& p, Divergence& d) {
  d.drift = judge_drift(p.scene, p.ei.law, d.extended->h, d.extended->e, d.noise + d.precision);
  if (!d.drift->applies) return;
  d.finding = DivergenceFinding::phase_drift;
  d.passed = d.drift->explained;
}

// Both engines follow their laws, yet the order is out of band: the scene's steps may be
// pre-asymptotic. Halves the finest step until the last order is in band (extend_sweep).
void extend(const Pair& p, Divergence& d, std::int64_t extension_steps) {
  const std::vector<double> h = d.measured_h();
  d.pre_asymptotic = pre_asymptotic_cause(p.scene, h.back());
  d.extended = extend_sweep(
      p.scene, h, d.measured_errors(), d.noise,
      extension_error(p.scene, p.engine, p.ei, p.ri, p.to_analytic, d.precision), extension_steps);
  d.finding = DivergenceFinding::extended;
  d.passed = d.extended->reached;
  if (!d.extended->reached && p.to_analytic) judge_phase_drift(p, d);
}

// The order over the measured steps, and what follows from it.
void judge_order(const Pair& p, Divergence& d, std::int64_t extension_steps) {
  const std::vector<double> h = d.measured_h(), e = d.measured_errors();
  if (h.size() < 2) {
    d.finding = DivergenceFinding::no_order;
    d.passed = true;
    return;
  }
  if (!p.to_analytic && e.back() == 0.0) {
    d.finding = DivergenceFinding::same_law;
    d.passed = true;
    return;
  }
  gather_rounding(d);
  d.order = estimate_order(h, e, d.noise);
  d.finding = DivergenceFinding::order;
  d.passed = d.order->first_order || (p.to_analytic && !d.order->measurable);
  if (d.passed || !d.order->measurable) return;
  if (d.first_departure()) {
    d.finding = DivergenceFinding::not_extended;
    return;
  }
  extend(p, d, extension_steps);
}

}  // namespace

Divergence measure_divergence(const Scene& scene, const EngineFactory& make,
                              const EngineFactory& reference, std::int64_t extension_steps) {
  std::unique_ptr<Engine> engine = make(), ref = reference();
  const EngineInfo ei = engine->info(), ri = ref->info();
  const Pair p{scene, *engine, *ref, ei, ri, ei.name == ri.name};
  Divergence d;
  d.engine = p.ei.name, d.reference = p.ri.name, d.to_analytic = p.to_analytic;
  if (p.to_analytic && !analytic_unavailable(scene).empty()) {
    d.no_closed_form = analytic_unavailable(scene);
    d.finding = DivergenceFinding::no_closed_form;
    d.passed = true;
    return d;
  }
  for (const Timestep& h : scene_sweep(scene))
    if (!measure_step(p, h, d.steps)) {
      d.finding = d.steps.back().failure.empty() ? DivergenceFinding::unexplained
                                                 : DivergenceFinding::run_failed;
      return d;
    }
  judge_order(p, d, extension_steps);
  return d;
}

}  // namespace dropcheck
