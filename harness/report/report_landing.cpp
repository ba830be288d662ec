// The landing part of a contact scene's section (harness/oracles/landing.hpp): first contact
// against the continuous model and the engine's own law, penetration, rebound, resting offset
// against what the engine documents (EngineInfo::rest_offset, docs/engines.md section 5),
// stillness.
#include "harness/report/report_landing.hpp"

#include <algorithm>
#include <cmath>

#include "harness/judge/turned_verdict.hpp"
#include "harness/oracles/landing.hpp"
#include "harness/report/report_contact.hpp"
#include "harness/report/report_format.hpp"
#include "harness/report/report_scene.hpp"

namespace dropcheck {
namespace {

std::string time_or_never(double t) {
  return std::isnan(t) ? "never" : sig(t, 4);
}

// "yes", "**NO**", or why stillness is not judged (the run ends too soon after first contact); for
// an engine with a climb path, whether the run climbs as that path does.
std::string still_cell(const LandingResult& l) {
  const LandingObservation& o = l.seen;
  if (l.expected.climb)
    return printf_string(l.expected.climb->replayed.empty()
                             ? "climbs at %.3g m/s as its law, %.2g m off it"
                             : "ends at %.3g m/s as its replayed force law, %.2g m off it",
                         l.expected.climb->climb, l.end.off_path) +
           (l.end.settled ? "" : ": **NO**");
  if (o.first_contact_step >= 0 && !o.still_judged)
    return printf_string("not judged (run ends %.3g s after contact)", o.after_contact);
  return o.still ? "yes" : "**NO**";
}

std::vector<std::string> landing_row(const SceneEvaluation& se, const EngineEvaluation& ev,
                                     const LandingResult& l) {
  const LandingObservation& o = l.seen;
  const bool touched = o.first_contact_step >= 0;
  if (landing_tunnel_verdict(se, ev, l) == TunnelVerdict::limit)
    return {ev.name,
            se.scene.bodies[l.setup.body].name,
            "tunnelled (no continuous collision: a limit)",
            time_or_never(l.setup.contact_time),
            time_or_never(l.law_contact_time),
            g3(o.deepest),
            "—",
            g3(o.rest_offset),
            g3(l.expected.rest_offset) + " ± " + g3(l.expected.tolerance),
            "not judged",
            "not judged"};
  return {ev.name,
          se.scene.bodies[l.setup.body].name,
          touched ? time_or_never(o.first_contact_time) : "never",
          time_or_never(l.setup.contact_time),
          time_or_never(l.law_contact_time),
          cell(o.deepest),
          cell(o.rebound - l.expected.rest_offset),
          cell(o.rest_offset),
          cell(l.expected.rest_offset) + " ± " + cell(l.expected.tolerance),
          l.end.rests ? "yes" : "**NO**",
          still_cell(l)};
}

// One sentence per body the single-body oracle leaves out (a stack), or "".
std::string exclusions(const Scene& scene) {
  std::string out;
  for (const LandingExclusion& e : landing_exclusions(scene))
    out += "- " + e.sentence(scene) + ".\n";
  return out.empty() ? out
                     : "Not judged here (stacks; `dropcheck stability` reports a body that ends "
                       "below one it started above as tunnelled):\n\n" +
                           out + "\n";
}

}  // namespace

TunnelVerdict landing_tunnel_verdict(const SceneEvaluation& se, const EngineEvaluation& ev,
                                     const LandingResult& l) {
  const StepEvaluation& st = ev.at_default();
  const Tunnelling law = discrete_tunnelling(ev.info.law, se.scene, st.h.seconds, l.setup);
  return judge_tunnelling(law, ev.info, st.run, l.setup);
}

namespace {

// A turning landing: compared for every engine, and judged step by step for an engine that
// declares where its contact acts on a turned box (harness/judge/turned_verdict.hpp).
std::string turning_section(const SceneEvaluation& se) {
  MarkdownTable t({"engine", "turned-box contact law", "steps", "starting in contact",
                   "corner within rounding of the face", "worst |dx| (m)", "worst |dv| (m/s)",
                   "worst angle (rad)", "worst |dw| (rad/s)", "follows"},
                  "llr");
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran() || ev.info.turned_contact == TurnedContact::not_declared) continue;
    const Trajectory& run = ev.at_default().run;
    if (run.status != RunStatus::ok) continue;
    const TurnedVerdict v = judge_turned_contact(se.scene, ev.info, run);
    if (!v.not_judged.empty()) {
      t.add({ev.name, describe(ev.info.turned_contact), "not judged: " + v.not_judged});
      continue;
    }
    t.add({ev.name, describe(ev.info.turned_contact), std::to_string(v.steps),
           std::to_string(v.contact_steps), std::to_string(v.undecided_steps), g3(v.worst.position),
           g3(v.worst.velocity), g3(v.worst.angle), g3(v.worst.spin),
           v.follows() ? "yes"
                       : "**NO**, from step " + std::to_string(v.first_departure) + " (" +
                             v.departure_quantity + ")"});
  }
  std::string out =
      "#### Landing\n\nA turning body meets the floor with a corner or an edge, and from there "
      "each engine's contact model decides: the flat-landing closed form does not apply, so the "
      "landing is compared (trajectories and divergence below). The divergence is attributed over "
      "the fall while the body's centre stays farther from the floor than its half-diagonal.\n\n";
  if (t.empty()) return out;
  return out +
         "An engine that declares where its contact acts on a turned box is judged by that law at "
         "every step of h = " +
         se.scene.timestep.text +
         ", each step taken from the run's own state the step before (a tumble amplifies rounding, "
         "so a law replayed from the start would part from a float run without a fault); a corner "
         "within rounding of the face is tried in contact and not (docs/contact.md, \"Tumbling "
         "landings\"):\n\n" +
         t.str() + "\n";
}

}  // namespace

std::string landing_section(const SceneEvaluation& se) {
  if (se.scene.world.contacts && needs_rotation(se.scene)) return turning_section(se);
  MarkdownTable t(
      {"engine", "body", "first contact t (s)", "closed form t (s)", "own law t (s)", "deepest (m)",
       "rebound above own rest (m)", "rest offset (m)", "expected (m)", "as expected", "still"},
      "llr");
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran()) continue;
    for (const LandingResult& l : ev.at_default().landings) t.add(landing_row(se, ev, l));
  }
  const std::string excluded = exclusions(se.scene);
  if (t.empty() && excluded.empty()) return {};
  // The bodies that fall alone onto their floor (none on or under another), with nothing but
  // gravity and the contact on them: no damping, no force.
  std::vector<FallingBody> falling;
  const std::vector<LandingExclusion> stacked = landing_exclusions(se.scene);
  const bool undamped = se.scene.world.damping_rate == 0.0;
  for (const LandingSetup& l : landing_setups(se.scene))
    if (undamped && !pushed(se.scene, l.body) &&
        std::none_of(stacked.begin(), stacked.end(),
                     [&](const LandingExclusion& x) { return x.body == l.body; }))
      falling.push_back({l.body, l.half_height, l.floor_top});
  return "#### Landing at h = " + se.scene.timestep.text +
         "\n\nFirst contact: first recorded step with the body's bottom at or below the "
         "floor's top, raised by the engine's expected rest offset where that is positive "
         "(Box2D's skin), as `dropcheck check` counts it; the closed form solves the continuous "
         "model for the geometric instant, the own law iterates the engine's discrete law with "
         "contacts ignored. Offsets are centre heights minus the geometric rest height (floor "
         "top + half extent); deepest < 0 is penetration; the rebound is measured above the "
         "engine's expected rest height. Still: |v| and the position range stay within 1 mm(/s) "
         "over the last 2 s, judged only when that window lies wholly after first contact; an "
         "engine whose push-out is capped (DART) climbs out of the floor for minutes instead, and "
         "is judged by its law's path at every step, its end the expected offset, as is an engine "
         "whose "
         "contact force law dropcheck steps as its integrator does (Simbody's compliant contact). "
         "A body that tunnels through the floor as its engine's own law predicts (no end-of-step "
         "position overlaps the floor) on an engine without continuous collision meets a limit "
         "of that engine, not a fault.\n\n" +
         (t.empty() ? "" : t.str() + "\n") + excluded + momentum_section(se, falling);
}

}  // namespace dropcheck
