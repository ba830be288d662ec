// The rotation part of a rotating scene's section: what each engine does to the conserved
// quantities (harness/judge/rotation_budget.hpp), the flips against the closed form
// (harness/oracles/free_rotation.hpp), and published figures reproduced by the rotational member
// that explains them (Scene::published, harness/oracles/own_rotation.hpp).
#include "harness/report/report_rotation.hpp"

#include <cmath>

#include "harness/core/rotation_metrics.hpp"
#include "harness/judge/rotation_budget.hpp"
#include "harness/oracles/own_rotation.hpp"
#include "harness/report/report_format.hpp"

namespace dropcheck {
namespace {

// The first dynamic body: the one the tables follow (the shipped rotating scenes have one).
std::size_t turning_body(const Scene& scene) {
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (!scene.bodies[i].is_static) return i;
  return 0;
}

// "+0.209 J" / "-0.202 J": signed, so gained and lost read apart.
std::string signed_joules(double e) {
  return printf_string("%+.3g J", e);
}

std::string budget_table(const SceneEvaluation& se, std::size_t body) {
  MarkdownTable t({"engine", "h", "max abs(dL)/abs(L0)", "rotational energy change",
                   "translational + potential change", "max abs(w_body - closed form) (rad/s)"},
                  "llr");
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran()) continue;
    for (const StepEvaluation& st : ev.sweep) {
      if (st.run.status != RunStatus::ok || !st.run.rotates) continue;
      const RotationBudget b = rotation_budget(se.scene, st.run, body);
      t.add({ev.name, st.h.text, sig(b.momentum_drift, 6),
             signed_joules(b.rotational_energy_change), signed_joules(b.linear_energy_change),
             cell(b.closed_form_error)});
    }
  }
  return t.empty() ? std::string() : t.str();
}

std::string times(const std::vector<double>& ts) {
  std::string out;
  for (double t : ts) out += (out.empty() ? "" : ", ") + sig(t, 4);
  return out.empty() ? "none" : out;
}

std::string flips_table(const SceneEvaluation& se, std::size_t body) {
  MarkdownTable t({"engine", "flips at h = " + se.scene.timestep.text + " (s)", "closed form (s)"},
                  "l");
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran() || ev.at_default().run.status != RunStatus::ok) continue;
    const RotationBudget b = rotation_budget(se.scene, ev.at_default().run, body);
    if (!b.closed_form || b.closed_form_flips.empty()) return {};
    t.add({ev.name, times(b.flips), times(b.closed_form_flips)});
  }
  return t.empty() ? std::string() : t.str();
}

std::string published_table(const SceneEvaluation& se, std::size_t body) {
  if (se.scene.published.empty()) return {};
  MarkdownTable t({"published by", "h", "published max abs(dL)/abs(L0)", "member (at its step)",
                   "member predicts", "why that member"},
                  "llrlrl");
  for (const PublishedFigure& p : se.scene.published)
    t.add(
        {p.engine, sig(p.dt, 4), sig(p.max_momentum_drift, 6),
         p.law + " (h = " + sig(p.law_dt, 4) + ")",
         sig(predicted_momentum_drift(se.scene, *parse_rotation_law_key(p.law), p.law_dt, body), 6),
         p.note});
  std::string sources;
  for (const PublishedFigure& p : se.scene.published)
    if (sources.find(p.source) == std::string::npos)
      sources += (sources.empty() ? "" : "; ") + p.source;
  return "Published figures for this scene (" + sources +
         "), each beside the rotational member that explains it, run by dropcheck at the step "
         "given; Debian's engines at the same step are in the table above.\n\n" +
         t.str() + "\n";
}

}  // namespace

std::string rotation_section(const SceneEvaluation& se) {
  if (!needs_rotation(se.scene) || se.scene.world.contacts) return {};
  const std::size_t body = turning_body(se.scene);
  const std::string budgets = budget_table(se, body);
  if (budgets.empty()) return {};
  const std::string flips = flips_table(se, body);
  return "#### Rotation of " + se.scene.bodies[body].name +
         "\n\nWorld angular momentum L = R*diag(I)*R^T*w, its largest drift from the start; the "
         "rotational energy w.L/2 and the translational plus potential energy m*v^2/2 - m*g.x, "
         "each as end minus start (+ gained, - lost): kept apart, so that the translational "
         "part cannot hide what the rotation does. Against the closed form (torque-free and "
         "(torque-free bodies, damped or not): the largest distance of the body-frame angular "
         "velocity. Every "
         "engine's own rotational law is judged by `dropcheck check` (own law).\n\n" +
         budgets + "\n" +
         (flips.empty()
              ? std::string()
              : "Flips (Dzhanibekov): the times at which the body-frame angular velocity along "
                "the intermediate axis changes sign, interpolated between samples.\n\n" +
                    flips + "\n") +
         published_table(se, body);
}

}  // namespace dropcheck
