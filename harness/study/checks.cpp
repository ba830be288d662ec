#include "harness/study/checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <tuple>

#include "harness/core/number_format.hpp"
#include "harness/core/timestep.hpp"
#include "harness/judge/attribution.hpp"
#include "harness/judge/bounce_verdict.hpp"
#include "harness/judge/landing_expectation.hpp"
#include "harness/judge/law_stability.hpp"
#include "harness/judge/metrics.hpp"
#include "harness/judge/own_law.hpp"
#include "harness/judge/slide_verdict.hpp"
#include "harness/judge/stack_verdict.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/judge/turned_verdict.hpp"
#include "harness/oracles/analytic.hpp"
#include "harness/oracles/contact_laws.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/oracles/landing.hpp"
#include "harness/oracles/own_arithmetic.hpp"
#include "harness/run/runner.hpp"
#include "harness/study/divergence.hpp"
#include "harness/study/sweep.hpp"

namespace dropcheck {
namespace {

std::string fmt(const char* format, double a, double b = 0.0, double c = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b, c);
  return buf;
}

std::string vec(const Vec3& v) {
  return fmt("(%.17g, %.17g, %.17g)", v.x(), v.y(), v.z());
}

CheckResult check_result(const Scene& scene, const std::string& engine, const std::string& check) {
  return {scene.name, engine, check, false, {}, {}};
}

// Where the verdict's worst departure lies, both states.
std::string worst_text(const OwnLawVerdict& v, const Trajectory& run, const Trajectory& own) {
  const BodyState& got = run.at(v.worst_sample, v.worst_body);
  const BodyState& want = own.at(v.worst_sample, v.worst_body);
  return "; worst at body '" + run.body_names[v.worst_body] + "' step " +
         std::to_string(run.recorded[v.worst_sample]) + ": engine x = " + vec(got.position) +
         " v = " + vec(got.velocity) + ", law x = " + vec(want.position) +
         " v = " + vec(want.velocity);
}

}  // namespace

std::vector<Timestep> conformance_steps(const Scene& scene) {
  return own_law_steps(scene);
}

CheckResult check_own_law(const Scene& scene, const EngineFactory& make, const Timestep& h) {
  std::unique_ptr<Engine> engine = make();
  const EngineInfo info = engine->info();
  CheckResult r = check_result(scene, info.name, "own law at h = " + h.text);
  const Trajectory run = run_scene(*engine, scene, h.seconds);
  const std::string unstable = law_instability(scene, info.law, h);
  if (run.status != RunStatus::ok) {
    r.message = std::string("run failed: ") + to_string(run.status) + ": " + run.failure;
    if (unstable.empty() || !blew_up(run)) return r;
  }
  if (!unstable.empty()) {
    // Its law blows up at this h: the engine blowing up too is the law's limit, provided it
    // followed the law up to where it stopped or the law left finite values.
    const OwnLawVerdict v = judge_while_law_finite(info, scene, run);
    r.passed = v.follows();
    r.limit = r.passed ? unstable : "";
    r.message += std::string(r.message.empty() ? "" : "; ") +
                 (r.passed ? "up to step " : unstable + ", but up to step ") +
                 std::to_string(v.compared_steps) +
                 (r.passed ? " it follows its law: " : " it departs from its law: ") + v.sentence();
    if (!r.passed) r.message += worst_text(v, run, predict_own_arithmetic(info, scene, h.seconds));
    return r;
  }
  const Trajectory own = predict_own_arithmetic(info, scene, h.seconds);
  const OwnLawVerdict v =
      judge_own_law(info, run, own, predict_discrete(info.law, scene, h.seconds));
  r.passed = v.follows();
  r.message = v.sentence();
  if (!r.passed) r.message += worst_text(v, run, own);
  return r;
}

namespace {

std::string orders_text(const std::vector<double>& orders) {
  std::string out;
  for (double p : orders) out += std::isfinite(p) ? fmt(" %.3f", p) : std::string(" undefined");
  return out;
}

// What the order leaves out (the steps where a law is unstable, and why the first one is), and
// how the two runs' rotations stand: the tail of every message over a whole sweep.
std::string sweep_notes(const Divergence& d) {
  std::string out;
  if (const DivergenceStep* first = d.first_left_out()) {
    std::string steps;
    for (const DivergenceStep& s : d.steps)
      if (!s.unstable.empty()) steps += (steps.empty() ? "" : ", ") + s.h.text;
    out = "; left out of the order: h = " + steps + " (" + first->unstable_engine + ": " +
          first->unstable + ")";
  }
  const DivergenceStep* apart = d.rotations_apart();
  if (!apart) return out;
  const Attribution& a = *apart->attribution;
  if (a.rotation_laws_differ())
    return out + "; rotation: the rotational laws differ (" + a.rotation_laws + ", " +
           g3(a.rotation_law_part) + " rad apart at h = " + apart->h.text +
           "), each engine follows its own";
  return out + "; rotation: one rotational law (" + a.rotation_laws + "), " + g3(a.rotation_total) +
         " rad apart at h = " + apart->h.text +
         " from each engine's rounding, amplified by the motion";
}

// " (expected 0.9-1.1)": the first-order band.
std::string band_text() {
  return fmt(" (expected %.1f-%.1f)", tolerance::kFirstOrderLow, tolerance::kFirstOrderHigh);
}

// The extended sweep: its order, why the scene's steps were pre-asymptotic, and how it ended.
std::string extension_text(const Divergence& d) {
  const ExtendedSweep& x = *d.extended;
  return x.estimate.text + band_text() + "; the scene's sweep" +
         (x.reached ? " is pre-asymptotic (" : " may be pre-asymptotic (") + d.pre_asymptotic +
         "): its orders were" + orders_text(d.order->orders) + "; extended by " +
         std::to_string(x.added) + " halving" + (x.added == 1 ? "" : "s") +
         (d.to_analytic ? "" : " (law part alone)") +
         (x.reached ? ", the last order is in band" : ", stopped: " + x.stopped);
}

// The message of the divergence check: what decided it, with its figures.
std::string divergence_message(const Divergence& d) {
  using F = DivergenceFinding;
  const DivergenceStep* last = d.steps.empty() ? nullptr : &d.steps.back();
  switch (d.finding) {
    case F::no_closed_form:
      return "no analytic solution (" + d.no_closed_form + "); nothing to converge to";
    case F::run_failed:
      return "run at h = " + last->h.text + " failed: " + last->failure;
    case F::unexplained:
      return "at h = " + last->h.text + ": " + last->attribution->sentence();
    case F::no_order:
      return "fewer than two steps of the sweep where the laws are stable: no order" +
             sweep_notes(d);
    case F::same_law:
      return (d.rotations_apart() ? "same linear law: divergence within rounding at every step"
                                  : "same discrete law: divergence within rounding at every step") +
             sweep_notes(d);
    case F::order:
      return d.order->text + band_text() +
             (d.order->measurable ? "" : ", at rounding level: order not measurable") +
             sweep_notes(d);
    case F::not_extended:
      return d.order->text + band_text() + "; not extended: " + d.engine +
             " departs from its own law at h = " + d.first_departure()->h.text + sweep_notes(d);
    case F::extended:
      return extension_text(d) + sweep_notes(d);
    case F::phase_drift:
      return extension_text(d) + sweep_notes(d) + "; " + d.drift->sentence();
  }
  return "";
}

}  // namespace

CheckResult check_divergence(const Scene& scene, const EngineFactory& make,
                             const EngineFactory& reference, std::int64_t extension_steps) {
  const Divergence d = measure_divergence(scene, make, reference, extension_steps);
  CheckResult r =
      check_result(scene, d.engine,
                   d.to_analytic ? "convergence to analytic" : "divergence from " + d.reference);
  r.passed = d.passed;
  r.limit = d.limit() ? d.drift->limit_text() : "";
  r.message = divergence_message(d);
  return r;
}

namespace {

// Appends `part` to `text`, "; "-separated.
void append(std::string& text, const std::string& part) {
  text += (text.empty() ? "" : "; ") + part;
}

// One judged body's landing figures against its expectations (harness/judge/
// landing_expectation.hpp); clears `passed` on a failure. Stillness is judged only over a window
// wholly after first contact.
std::string landing_text(const Trajectory& run, const LandingSetup& setup, const EngineInfo& info,
                         const Scene& scene, const Timestep& h, bool& passed) {
  const StillCriteria still;
  const LandingObservation o = observe_landing(run, setup, still);
  const std::int64_t law_step = discrete_contact_step(info.law, scene, h.seconds, setup);
  const bool on_time = o.first_contact_step >= 0 &&
                       std::abs(o.first_contact_step - law_step) <= tolerance::kContactStepSlack;
  const LandingExpectation expected = landing_expectation(info, scene, h.seconds, setup);
  const double rebound = o.rebound - expected.rest_offset;  // above the engine's own rest height
  // A climb path is followed at every step, its first contact sample included (which may sit up
  // to the floor shift above the path's end): the rebound limit is for bodies that come to rest.
  const LandingEnd end = judge_landing_end(run, setup, o, expected, info, still);
  const bool no_rebound = !end.rebounds;
  passed = passed && on_time && no_rebound && end.rests && end.settled;
  return fmt("first contact at step %.0f (law: step %.0f; continuous t = %.4f s)",
             double(o.first_contact_step), double(law_step), setup.contact_time) +
         (on_time ? "" : " MORE THAN ONE STEP OFF") +
         fmt(", rebound %.3g m above rest (limit %.0e)", rebound, tolerance::kMaxRebound) +
         (no_rebound ? "" : " TOO HIGH") +
         fmt(", rest offset %.3g m (expected %.3g +- %.3g)", o.rest_offset, expected.rest_offset,
             expected.tolerance) +
         (end.rests ? "" : " OUT OF RANGE") + ", " + end.text +
         (end.departure.step >= 0 ? "; " + end.departure.sentence() : std::string());
}

// What is judged of a landing with no closed form (`why`): the run ends, and every dynamic body
// ends with its centre above the top of the highest static body below it (a body that fell
// through would end under it).
CheckResult floor_held(const Scene& scene, const Trajectory& run, CheckResult& r,
                       const std::string& why) {
  r.message = why;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Body& b = scene.bodies[i];
    if (b.is_static) continue;
    double floor_top = -INFINITY;
    for (const Body& s : scene.bodies)
      if (s.is_static && s.position.y() < b.position.y())
        floor_top = std::max(floor_top, top_of(s));
    const double y = run.final_state(i).position.y();
    r.message += "; " + b.name + fmt(" ends at y = %.6g m", y);
    if (y < floor_top) {
      r.passed = false;
      r.message += fmt(" BELOW the floor's top (%.6g m): fell through", floor_top);
    }
  }
  return r;
}

// A turning body meets the floor with a corner or an edge, and each engine's contact model decides
// what follows: no closed form to judge the landing by. An engine that declares where its contact
// acts on a turned box (EngineInfo::turned_contact) is judged by that law at every step.
CheckResult turning_landing(const Scene& scene, const EngineInfo& info, const Trajectory& run,
                            CheckResult& r) {
  if (info.turned_contact == TurnedContact::not_declared)
    return floor_held(scene, run, r,
                      "a turning body's landing has no closed form (corner or edge first, then "
                      "each engine's contact model): compared in the report, not judged");
  const TurnedVerdict v = judge_turned_contact(scene, info, run);
  floor_held(scene, run, r, v.sentence());
  if (!v.follows()) r.passed = false;
  return r;
}

}  // namespace

namespace {

// The one run of a contact check named `what` ("landing", "slide") at h: its result, passed so far,
// or failed with the reason when the run did not finish (then `run` is empty).
struct ContactRun {
  CheckResult result;
  EngineInfo info;
  std::optional<Trajectory> run;
};

ContactRun contact_run(const Scene& scene, const EngineFactory& make, const Timestep& h,
                       const std::string& what) {
  std::unique_ptr<Engine> engine = make();
  ContactRun c{
      check_result(scene, engine->info().name, what + " at h = " + h.text), engine->info(), {}};
  Trajectory run = run_scene(*engine, scene, h.seconds);
  if (run.status != RunStatus::ok) {
    c.result.message = std::string("run failed: ") + to_string(run.status) + ": " + run.failure;
    return c;
  }
  c.result.passed = true;
  c.run = std::move(run);
  return c;
}

}  // namespace

CheckResult check_landing(const Scene& scene, const EngineFactory& make, const Timestep& h) {
  ContactRun c = contact_run(scene, make, h, "landing");
  if (!c.run) return c.result;
  CheckResult& r = c.result;
  const EngineInfo& info = c.info;
  const Trajectory& run = *c.run;
  if (needs_rotation(scene)) return turning_landing(scene, info, run, r);
  if (scene.world.gravity.x() != 0.0 || scene.world.gravity.z() != 0.0)
    return floor_held(scene, run, r,
                      "gravity has a part along the floor, so a landing body slides on (only "
                      "slides are judged there: docs/contact.md)");
  const std::vector<LandingSetup> setups = engine_landing_setups(scene, info);
  std::vector<std::string> limits;
  for (const LandingSetup& setup : setups) {
    const std::string body = run.body_names[setup.body];
    const Tunnelling tunnel = discrete_tunnelling(info.law, scene, h.seconds, setup);
    const TunnelVerdict through = judge_tunnelling(tunnel, info, run, setup);
    if (through == TunnelVerdict::limit) {
      limits.push_back((setups.size() > 1 ? "'" + body + "' " : "") + tunnel.sentence() +
                       "; no continuous collision");
      append(r.message,
             body + ": tunnelled through the floor as its own law predicts (step " +
                 std::to_string(tunnel.step) + ")" +
                 fmt(", final centre %.3g m below the floor's bottom; not judged further",
                     setup.floor_bottom - run.final_state(setup.body).position.y()));
      continue;
    }
    append(r.message, body + ": " + landing_text(run, setup, info, scene, h, r.passed));
    if (through == TunnelVerdict::fault) {
      r.passed = false;
      r.message += " TUNNELLED although the engine declares continuous collision";
    }
  }
  for (const LandingExclusion& e : landing_exclusions(scene)) append(r.message, e.sentence(scene));
  if (setups.empty())
    append(r.message,
           scene.world.gravity.x() != 0.0 || scene.world.gravity.z() != 0.0
               ? "no body is judged here: gravity has a part along the floor, so a landing body "
                 "slides on (only slides are judged there: docs/contact.md)"
               : "no body is judged here: a stack, a slide or a bounce is judged by its own "
                 "contact law where the scene holds one (docs/contact.md)");
  for (const std::string& l : limits) append(r.limit, l);
  return r;
}

namespace {

// A contact check named `what` over the scene's `setups`: judge(run, setup, info) gives whether the
// body passes and the sentence that says why, one line per judged body.
template <typename Setup, typename Judge>
CheckResult check_contact_law(const Scene& scene, const EngineFactory& make, const Timestep& h,
                              const std::string& what, const std::vector<Setup>& setups,
                              Judge&& judge) {
  ContactRun c = contact_run(scene, make, h, what);
  if (!c.run) return c.result;
  CheckResult& r = c.result;
  const Trajectory& run = *c.run;
  for (const Setup& s : setups) {
    const auto [passes, sentence, limit] = judge(run, s, c.info);
    r.passed = r.passed && passes;
    append(r.message, run.body_names[s.body] + ": " + sentence);
    if (!limit.empty()) append(r.limit, run.body_names[s.body] + ": " + limit);
  }
  return r;
}

}  // namespace

CheckResult check_slide(const Scene& scene, const EngineFactory& make, const Timestep& h) {
  return check_contact_law(scene, make, h, "slide", slide_setups(scene),
                           [&](const Trajectory& run, const SlideSetup& s, const EngineInfo& i) {
                             const SlideVerdict v = judge_slide(run, scene, s, i, h.seconds);
                             return std::tuple(
                                 v.passes(), v.sentence(),
                                 v.rounding_limited() ? v.limit_text() : std::string());
                           });
}

CheckResult check_bounce(const Scene& scene, const EngineFactory& make, const Timestep& h) {
  return check_contact_law(scene, make, h, "bounce", bounce_setups(scene),
                           [&](const Trajectory& run, const BounceSetup& s, const EngineInfo& i) {
                             const BounceVerdict v = judge_bounce(run, scene, s, i, h.seconds);
                             return std::tuple(v.follows, v.sentence(), std::string());
                           });
}

CheckResult check_stack(const Scene& scene, const EngineFactory& make, const Timestep& h) {
  ContactRun c = contact_run(scene, make, h, "stack");
  if (!c.run) return c.result;
  CheckResult& r = c.result;
  const Trajectory& run = *c.run;
  for (const StackSetup& s : stack_setups(scene)) {
    std::string text;
    const std::vector<StackBodyVerdict> verdicts = judge_stack(run, s, c.info, h.seconds);
    for (const StackBodyVerdict& v : verdicts) {
      r.passed = r.passed && v.passes();
      text += (text.empty() ? "" : "; ") + run.body_names[v.body] + " " + v.sentence();
    }
    append(r.message, "stack from '" + run.body_names[s.body] + "' up: " + text);
    const bool squeezed = std::any_of(verdicts.begin(), verdicts.end(), [](const auto& v) {
      return v.unheld && v.above_floor && !v.holds();
    });
    if (squeezed)
      append(r.limit, "the stack from '" + run.body_names[s.body] + "' up is " +
                          verdicts.front().limit_text());
  }
  return r;
}

std::vector<CheckResult> check_scene(const Scene& scene, const EngineFactory& make,
                                     const EngineFactory& reference) {
  std::vector<CheckResult> out;
  if (!make()->cannot_run(scene).empty()) return out;
  if (scene.world.contacts) {
    // Each contact law the scene holds, then the landing of every other body over a floor (or
    // the landing check alone, which names what it leaves out).
    if (!slide_setups(scene).empty()) out.push_back(check_slide(scene, make, scene.timestep));
    if (!bounce_setups(scene).empty()) out.push_back(check_bounce(scene, make, scene.timestep));
    if (!stack_setups(scene).empty()) out.push_back(check_stack(scene, make, scene.timestep));
    if (out.empty() || !engine_landing_setups(scene, make()->info()).empty())
      out.push_back(check_landing(scene, make, scene.timestep));
    return out;
  }
  for (const Timestep& h : own_law_steps(scene)) out.push_back(check_own_law(scene, make, h));
  out.push_back(check_divergence(scene, make, reference));
  return out;
}

}  // namespace dropcheck
