#include "harness/report/report_contact.hpp"

#include <algorithm>

#include "harness/core/number_format.hpp"
#include "harness/judge/bounce_verdict.hpp"
#include "harness/judge/contact_departures.hpp"
#include "harness/judge/slide_verdict.hpp"
#include "harness/judge/stack_verdict.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/oracles/normal_impulses.hpp"
#include "harness/report/report_format.hpp"

namespace dropcheck {
std::vector<ContactLaw> departed_laws(const SceneEvaluation& se, const EngineEvaluation& ev) {
  std::vector<ContactLaw> out;
  if (!ev.ran() || ev.at_default().run.status != RunStatus::ok) return out;
  for (const ContactDeparture& d :
       contact_departures(se.scene, ev.at_default().run, ev.info, se.scene.timestep.seconds))
    if (std::find(out.begin(), out.end(), d.law) == out.end()) out.push_back(d.law);
  return out;
}

namespace {

// "62" / "never moves" / "slides on": a path's stop step.
std::string stop_cell(const SlideObservation& o) {
  if (o.stop_step < 0) return "slides on";
  return o.stop_step == 0 ? "never moves" : std::to_string(o.stop_step);
}

// The continuous answer: "1.0204 s, 2.551 m" to a stop, else the distance at the run's end.
std::string closed_form_cell(const SlideVerdict& v) {
  if (v.law.stops && v.law.stop_step > 0)
    return printf_string("stops at %.5g s, %.5g m", v.law.stop_time, v.law.distance);
  return printf_string("%.7g m by the end", v.end_continuous);
}

}  // namespace

namespace {

// "0.014 (step 53)": a figure and the step where it is worst.
std::string at_step(double figure, std::int64_t step) {
  return step > 0 ? printf_string("%.2g (step %lld)", figure, static_cast<long long>(step))
                  : std::string("0");
}

// Calls f(ev, run) for each engine whose default-step run finished and kept every step: what the
// momentum tables read.
template <class F>
void each_kept_run(const SceneEvaluation& se, F f) {
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran() || ev.at_default().run.status != RunStatus::ok) continue;
    if (ev.at_default().run.keeps_every_step()) f(ev, ev.at_default().run);
  }
}

// Every engine's slides certified from their momentum (harness/oracles/slide_impulses.hpp),
// whatever its solver: Coulomb's law on the normal impulses the run shows.
std::string coulomb_section(const SceneEvaluation& se, const std::vector<SlideSetup>& slides) {
  MarkdownTable t({"engine", "body", "slipping steps", "median F/(mu*N)", "whole slide F/(mu*N)",
                   "worst below mu*N", "worst above mu*N", "held steps", "creep (m/s)", "N/(m*g*h)",
                   "contact pulls"},
                  "ll");
  const double h = se.scene.timestep.seconds;
  each_kept_run(se, [&](const EngineEvaluation& ev, const Trajectory& run) {
    for (const SlideSetup& s : slides) {
      const CoulombCertificate c =
          coulomb_certificate(slide_impulses(run.body_states(s.body), s, h), s.mu, s.g, h, 0.0,
                              machine_epsilon(ev.info.scalar));
      t.add({ev.name, se.scene.bodies[s.body].name, std::to_string(c.slipping),
             c.slipping ? printf_string("%.9g", c.median_ratio) : kNone,
             c.slipping ? printf_string("%.6g", c.mean_ratio) : kNone,
             at_step(c.worst_short, c.worst_short_step), at_step(c.worst_over, c.worst_over_step),
             std::to_string(c.held), at_step(c.creep, c.creep_step),
             printf_string("%.3g .. %.3g", c.min_normal, c.max_normal),
             c.pull_step > 0 ? "**step " + std::to_string(c.pull_step) + "**" : "no"});
    }
  });
  return "#### Coulomb's law from the momentum, every engine\n\nEach step's contact impulse is "
         "what gravity does not explain of the body's velocity change, m*(v_n - v_(n-1) - g*h): "
         "its part along the floor's normal is the normal impulse N, the rest the friction F. A "
         "step whose slip needs more than mu*N to cancel slips, with F = mu*N against the slip; "
         "any other is held, with no slip left (the creep is what is left). Below and above "
         "mu*N are relative, on one step; an exact solver is mu*N to rounding on every step, an "
         "iterative one strays on some (docs/contact.md). No engine has to expose its impulses "
         "for this.\n\n" +
         t.str() + "\n";
}

}  // namespace

std::string momentum_section(const SceneEvaluation& se, const std::vector<FallingBody>& bodies) {
  if (bodies.empty()) return {};
  MarkdownTable t({"engine", "body", "pushing steps", "pulls (N < 0)", "widest gap pushed at (m)",
                   "deepest overlap (m)", "largest rebound / approach"},
                  "ll");
  const double h = se.scene.timestep.seconds;
  const double g = -se.scene.world.gravity.y();
  each_kept_run(se, [&](const EngineEvaluation& ev, const Trajectory& run) {
    for (const FallingBody& b : bodies) {
      const NormalCertificate c =
          normal_certificate(run.body_states(b.body), b.bottom_offset, b.floor_top, g, h,
                             machine_epsilon(ev.info.scalar));
      t.add({ev.name, se.scene.bodies[b.body].name, std::to_string(c.contact_steps),
             c.pull_step > 0 ? printf_string("**step %lld** (%.3g of m*g*h)",
                                             static_cast<long long>(c.pull_step), c.worst_pull)
                             : std::string("no"),
             at_step(c.widest_gap, c.widest_gap_step), at_step(c.deepest, c.deepest_step),
             c.rebound_step > 0 ? printf_string("%.4g (step %lld)", c.rebound,
                                                static_cast<long long>(c.rebound_step))
                                : kNone});
    }
  });
  if (t.empty()) return {};
  return "#### Contact from the momentum, every engine\n\nEach step's normal impulse is what "
         "gravity does not explain of the body's vertical velocity change, m*(v_n - v_(n-1) + "
         "g*h), set beside the body's gap to the floor after the step: a contact pushes and never "
         "pulls (Signorini), pushes only when touching (an engine with a contact distance pushes "
         "from a gap on purpose: Bullet's speculative contact), and an impact's rebound over its "
         "approach is at most the restitution (more is energy made). No engine has to expose its "
         "impulses for this (docs/contact.md).\n\n" +
         t.str() + "\n";
}

std::string slide_section(const SceneEvaluation& se) {
  const std::vector<SlideSetup> slides = slide_setups(se.scene);
  if (slides.empty()) return {};
  MarkdownTable t({"engine", "body", "its law", "stop step", "distance (m)", "its law: stop step",
                   "its law: distance (m)", "clamp law: stop step", "closed form",
                   "off its law (m)", "follows its law"},
                  "lll");
  const double h = se.scene.timestep.seconds;
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran() || ev.at_default().run.status != RunStatus::ok) continue;
    for (const SlideSetup& s : slides) {
      const SlideVerdict v = judge_slide(ev.at_default().run, se.scene, s, ev.info, h);
      const std::string law =
          v.solver ? describe(*v.solver)
                   : std::string(to_string(v.model)) + "'s clamp law" +
                         (v.soft.cfm > 0.0 ? " under " + describe(v.soft) : std::string());
      t.add({ev.name, se.scene.bodies[s.body].name, law, stop_cell(v.seen),
             printf_string("%.7g", v.seen.distance), v.exact ? stop_cell(v.law_seen) : kNone,
             v.exact ? printf_string("%.7g", v.law_seen.distance) : kNone,
             v.exact ? stop_cell(v.solver ? v.clamp_seen : v.law_seen) : kNone,
             v.exact ? closed_form_cell(v) : kNone,
             v.exact ? printf_string("%.2g", v.off_law) : kNone,
             !v.exact               ? "not judged: " + v.not_judged
             : v.follows            ? "yes"
             : v.rounding_limited() ? "limit: " + v.limit_text()
             : !v.instead.empty()   ? "**NO**: " + v.instead
                                    : std::string("**NO**")});
    }
  }
  return "#### Slides at h = " + se.scene.timestep.text +
         "\n\nThe stop step is the first step from which the speed along the floor stays at most " +
         printf_string("%.0e", tolerance::kStoppedSpeed) +
         " m/s; distances are along the slip. The clamp law is the ideal discrete slide of the "
         "engine's friction model: per step v_free = v + pull*h (gravity's part along the floor), "
         "then the friction impulse cancels the slip if it can and otherwise takes grip*h off it "
         "(a cone grips mu*g, a box pyramid each tangent axis by mu*g, a sum pyramid shares mu*g "
         "between them: docs/contact.md). An engine whose solver stops short of the clamp law is "
         "judged against its own solver instead: fixed iterations replayed in its own arithmetic, "
         "or a step problem re-solved (the 'its law' column names which); the clamp law's stop "
         "beside it shows what the solver leaves. The run is compared "
         "with its law at every step, within " +
         printf_string("%.0e", tolerance::kSlideDistance) + " m.\n\n" + t.str() + "\n" +
         coulomb_section(se, slides);
}

std::string bounce_section(const SceneEvaluation& se) {
  const std::vector<BounceSetup> bounces = bounce_setups(se.scene);
  if (bounces.empty()) return {};
  std::vector<FallingBody> falling;
  for (const BounceSetup& s : bounces) falling.push_back({s.body, s.radius, s.floor_top});
  const double h = se.scene.timestep.seconds;
  MarkdownTable t(
      {"engine", "body", "contact step", "in (m/s)", "out (m/s)", "apexes", "its law: apexes",
       "ideal law: apexes", "off its law (m)", "why its law is off the ideal", "follows its law"},
      "ll");
  std::string closed;
  for (const BounceSetup& s : bounces) {
    const Bounce b = bounce(s.h0, s.e, s.g, h);
    closed += (closed.empty() ? "" : "; ") + se.scene.bodies[s.body].name + ": continuous apexes " +
              apex_text(b.apexes) + printf_string(", at rest after %.5g s", b.time_to_rest);
  }
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran() || ev.at_default().run.status != RunStatus::ok) continue;
    for (const BounceSetup& s : bounces) {
      const BounceVerdict v = judge_bounce(ev.at_default().run, se.scene, s, ev.info, h);
      std::string why = v.law_to_ideal > tolerance::kBouncePath ? "" : kNone;
      for (std::size_t i = 0; i < v.causes.size(); ++i) why += (i ? " and " : "") + v.causes[i];
      t.add({ev.name, se.scene.bodies[s.body].name,
             v.seen.contact_step < 0 ? "never" : std::to_string(v.seen.contact_step),
             printf_string("%.4g", v.seen.speed_in), printf_string("%.4g", v.seen.speed_out),
             apex_text(v.seen.apexes), apex_text(v.predicted.apexes), apex_text(v.ideal.apexes),
             printf_string("%.2g", v.worst_gap), why,
             !v.not_judged.empty() ? "not judged: " + v.not_judged
             : v.follows
                 ? "yes"
                 : printf_string("**NO**: step %lld", static_cast<long long>(v.first_step)) +
                       (v.instead.empty() ? "" : ", " + v.instead)});
    }
  }
  return "#### Bounces at h = " + se.scene.timestep.text +
         "\n\nThe contact step is the first step that ends with the sphere in the floor; out is "
         "its "
         "upward speed one step later; an apex is the highest point of the sphere's lowest point "
         "over the floor in a flight. Each engine is judged step by step against its own bounce "
         "law, within " +
         printf_string("%.0e", tolerance::kBouncePath) +
         " m: the ideal law (restitution of the speed the contact step ended with) and the members "
         "its contact adds, named where they move its path off the ideal one (docs/contact.md). "
         "The closed form: " +
         closed + ".\n\n" + t.str() + "\n" + momentum_section(se, falling);
}

std::string stack_section(const SceneEvaluation& se) {
  const std::vector<StackSetup> stacks = stack_setups(se.scene);
  if (stacks.empty()) return {};
  const double h = se.scene.timestep.seconds;
  MarkdownTable t(
      {"engine", "body", "level", "sink (m)", "its law: sink (m)", "rest offset (m)", "drift (m)",
       "last 2 s: speed (m/s)", "last 2 s: range (m)", "its stack law", "holds"},
      "ll");
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran() || ev.at_default().run.status != RunStatus::ok) continue;
    for (const StackSetup& s : stacks)
      for (const StackBodyVerdict& v : judge_stack(ev.at_default().run, s, ev.info, h)) {
        const auto mark = [](bool ok, const std::string& text) {
          return ok ? text : "**" + text + "**";
        };
        t.add({ev.name, se.scene.bodies[v.body].name, std::to_string(v.level),
               mark(v.sink_ok, printf_string("%.4g", v.sink)),
               printf_string("%.4g", v.predicted.sink), printf_string("%.4g", v.predicted.offset),
               mark(v.drift_ok, printf_string("%.2g", v.drift)),
               mark(v.still_ok, printf_string("%.2g", v.still.speed)),
               mark(v.still_ok, printf_string("%.2g", v.still.range)), stack_law_text(ev.info),
               v.holds()                   ? "yes"
               : v.unheld && v.above_floor ? "no: " + v.limit_text() + " (a limit)"
               : v.unheld                  ? std::string("**NO**: through the floor")
                                           : std::string("**NO**")});
      }
  }
  return "#### Stacks at h = " + se.scene.timestep.text +
         "\n\nThe ideal stack does not move: every body stays at its geometric rest height. Each "
         "engine is held to its stack law: the steady-state sink of the contacts under a body "
         "(a compliant or soft contact sinks under the weight it carries), its surfaces' rest "
         "offset, and the drift and stillness its solver is stated to leave; a load its solver's "
         "sweeps cannot hold is a named limit (docs/contact.md). Sink is the rest height plus the "
         "offset minus the final height; drift the largest horizontal distance from the "
         "start.\n\n" +
         t.str() + "\n";
}

}  // namespace dropcheck
