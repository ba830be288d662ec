// The landing part of a contact scene's section (harness/oracles/landing.hpp): first contact
// against the continuous model and the engine's own law, penetration, rebound, resting offset
// against what the engine documents (EngineInfo::rest_offset, docs/engines.md section 5),
// stillness.
#include "harness/report/report_landing.hpp"

#include <cmath>

#include "harness/report/report_format.hpp"
#include "harness/report/report_scene.hpp"

namespace dropcheck {
namespace {

std::string time_or_never(double t) {
  return std::isnan(t) ? "never" : sig(t, 4);
}

std::vector<std::string> landing_row(const EngineEvaluation& ev, const Scene& scene,
                                     const LandingResult& l) {
  const LandingObservation& o = l.seen;
  const bool touched = o.first_contact_step >= 0;
  return {ev.name,
          scene.bodies[l.setup.body].name,
          touched ? time_or_never(o.first_contact_time) : "never",
          time_or_never(l.setup.contact_time),
          time_or_never(l.law_contact_time),
          cell(o.deepest),
          cell(o.rebound - ev.info.rest_offset),
          cell(o.rest_offset),
          cell(ev.info.rest_offset) + " ± " + cell(ev.info.rest_tolerance),
          rest_offset_expected(ev, l) ? "yes" : "**NO**",
          o.still ? "yes" : "**NO**"};
}

}  // namespace

bool rest_offset_expected(const EngineEvaluation& ev, const LandingResult& l) {
  return std::abs(l.seen.rest_offset - ev.info.rest_offset) <= ev.info.rest_tolerance;
}

std::string landing_section(const SceneEvaluation& se) {
  MarkdownTable t(
      {"engine", "body", "first contact t (s)", "closed form t (s)", "own law t (s)", "deepest (m)",
       "rebound above own rest (m)", "rest offset (m)", "expected (m)", "as expected", "still"},
      "llr");
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran()) continue;
    for (const LandingResult& l : ev.at_default().landings) t.add(landing_row(ev, se.scene, l));
  }
  if (t.empty()) return {};
  return "#### Landing at h = " + se.scene.timestep.text +
         "\n\nFirst contact: first recorded step with the body's bottom at or below the "
         "floor's top, raised by the engine's expected rest offset where that is positive "
         "(Box2D's skin), as `dropcheck check` counts it; the closed form solves the continuous "
         "model for the geometric instant, the own law iterates the engine's discrete law with "
         "contacts ignored. Offsets are centre heights minus the geometric rest height (floor "
         "top + half extent); deepest < 0 is penetration; the rebound is measured above the "
         "engine's expected rest height. Still: |v| and the position range stay within 1 mm(/s) "
         "over the last 2 s.\n\n" +
         t.str() + "\n";
}

}  // namespace dropcheck
