// The ten-second view of a scene: engines run, the largest divergence from the reference with a
// one-word cause, and a verdict that flags what needs a person (failed, clamped, unexplained, off
// its own law).
#include "harness/report/report_summary.hpp"

#include <cmath>

#include "harness/oracles/contact_laws.hpp"
#include "harness/report/report_contact.hpp"
#include "harness/report/report_format.hpp"
#include "harness/report/report_landing.hpp"
#include "harness/report/report_scene.hpp"

namespace dropcheck {
namespace {

// "5/6 (not box2d)": engines that ran out of all listed.
std::string engines_run(const SceneEvaluation& se) {
  std::size_t ran = 0;
  std::string missing;
  for (const EngineEvaluation& ev : se.engines) {
    if (ev.ran())
      ++ran;
    else
      missing += (missing.empty() ? "" : ", ") + ev.name;
  }
  std::string s = printf_string("%zu/%zu", ran, se.engines.size());
  return missing.empty() ? s : s + " (not " + missing + ")";
}

// The engine farthest from the reference at the default step, or nullptr.
const EngineEvaluation* farthest(const SceneEvaluation& se) {
  const EngineEvaluation* best = nullptr;
  double worst = -1.0;
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran() || !ev.at_default().vs_reference) continue;
    const double d = ev.at_default().vs_reference->max_dx;
    if (d > worst || std::isnan(d)) worst = d, best = &ev;
  }
  return best;
}

// Beyond rounding from its own law at some step of the sweep: an adapter bug.
bool off_own_law(const EngineEvaluation& ev) {
  for (const StepEvaluation& st : ev.sweep)
    if (st.own_law && !st.own_law->follows()) return true;
  return false;
}

bool unexplained(const EngineEvaluation& ev) {
  for (const StepEvaluation& st : ev.sweep)
    if (st.attribution && !st.attribution->explained()) return true;
  return false;
}

// Landing flags at the default step: a resting offset outside the engine's band, or not still.
// A body that tunnelled as a limit (no continuous collision) is neither; a run too short after
// first contact to judge stillness is not restless (as `dropcheck check` decides).
bool off_rest(const SceneEvaluation& se, const EngineEvaluation& ev) {
  for (const LandingResult& l : ev.at_default().landings)
    if (landing_tunnel_verdict(se, ev, l) != TunnelVerdict::limit && !l.end.rests) return true;
  return false;
}

bool restless(const SceneEvaluation& se, const EngineEvaluation& ev) {
  for (const LandingResult& l : ev.at_default().landings)
    if (landing_tunnel_verdict(se, ev, l) != TunnelVerdict::limit && !l.end.settled) return true;
  return false;
}

bool tunnelled(const SceneEvaluation& se, const EngineEvaluation& ev) {
  for (const LandingResult& l : ev.at_default().landings)
    if (landing_tunnel_verdict(se, ev, l) == TunnelVerdict::limit) return true;
  return false;
}

bool clamped(const EngineEvaluation& ev) {
  for (const StepEvaluation& st : ev.sweep)
    if (st.run.clamped_steps) return true;
  return false;
}

// "FAILED: box2d; UNEXPLAINED: ode", or "ok". Each flag names the engines it concerns.
std::string verdict(const SceneEvaluation& se) {
  std::string failed, clamps, unexp, offlaw, rest, moving, tunnels, slides, bounces, stacks,
      landings;
  auto add = [](std::string& list, const std::string& name) {
    list += (list.empty() ? "" : ", ") + name;
  };
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran()) continue;
    if (ev.first_failure()) add(failed, ev.name);
    if (clamped(ev)) add(clamps, ev.name);
    if (unexplained(ev)) add(unexp, ev.name);
    if (off_own_law(ev)) add(offlaw, ev.name);
    if (off_rest(se, ev)) add(rest, ev.name);
    if (restless(se, ev)) add(moving, ev.name);
    if (tunnelled(se, ev)) add(tunnels, ev.name);
    for (const ContactLaw law : departed_laws(se, ev))
      add(law == ContactLaw::slide    ? slides
          : law == ContactLaw::bounce ? bounces
          : law == ContactLaw::stack  ? stacks
                                      : landings,
          ev.name);
  }
  std::string v;
  auto flag = [&v](const char* what, const std::string& list) {
    if (!list.empty()) v += (v.empty() ? "" : "; ") + std::string(what) + ": " + list;
  };
  flag("**FAILED**", failed);
  flag("**UNEXPLAINED**", unexp);
  flag("**OFF OWN LAW**", offlaw);
  flag("**CLAMPED**", clamps);
  flag("**REST OFFSET**", rest);
  flag("**NOT STILL**", moving);
  flag("**OFF SLIDE LAW**", slides);
  flag("**OFF BOUNCE LAW**", bounces);
  flag("**OFF STACK LAW**", stacks);
  flag("**OFF TURNED-BOX LAW**", landings);
  flag("tunnelled, no continuous collision (a limit)", tunnels);
  if (se.reference.empty()) flag("**NOT RUN**", "every engine");
  return v.empty() ? "ok" : v;
}

}  // namespace

std::string divergence_cause(const SceneEvaluation& se, const EngineEvaluation& ev) {
  const StepEvaluation& st = ev.at_default();
  if (st.run.status != RunStatus::ok) return "failed";
  const EngineEvaluation* ref = se.find(se.reference);
  if (ref && ref->at_default().run.status != RunStatus::ok) return "reference-failed";
  const bool none = st.vs_reference && st.vs_reference->max_dx == 0.0;
  if (!st.attribution) return none ? "identical" : "contacts";
  const Attribution& a = *st.attribution;
  if (!a.explained()) return "UNEXPLAINED (" + a.blamed() + " left its law)";
  // With contacts the attribution covers the fall only: when the gap over the whole run is more
  // than the fall's by over 10%, it opened at the landing.
  // A turning body: whether the two rotational members differ is a cause of its own.
  const std::string turn = a.rotation_laws_differ() ? " + rotational law" : "";
  // A bounce that opens the gap is the two engines' bounce laws (their members: the bounce table).
  if (st.attributed_until >= 0.0 && st.vs_reference->max_dx > 1.1 * a.total + a.budget)
    return (bounce_setups(se.scene).empty() ? "landing" : "bounce law") + turn;
  if (a.total == 0.0) return turn.empty() ? "identical" : "rotational law";
  // Explained: the laws' difference beyond rounding is what their members differ in (the damping
  // order, the position update); the rest is precision.
  if (a.law_part <= a.budget || a.law_difference.empty()) return "precision" + turn;
  return a.law_difference + turn;
}

SceneSummary summarize(const SceneEvaluation& se) {
  SceneSummary s;
  s.engines_run = engines_run(se);
  s.divergence = kNone;
  s.cause = kNone;
  if (const EngineEvaluation* far = farthest(se)) {
    s.divergence = far->name + " " + length(far->at_default().vs_reference->max_dx);
    if (se.reference_note.size()) s.divergence += " (from " + se.reference + ")";
    s.cause = divergence_cause(se, *far);
  }
  s.verdict = verdict(se);
  return s;
}

}  // namespace dropcheck
