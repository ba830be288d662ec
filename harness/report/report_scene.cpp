// One scene's section of the report: what it tests and leaves out, then the figures, each table
// showing only the metrics that apply to the scene (no analytic columns without a closed form, no
// law columns with contacts). Rows: engines in registry order, then bodies in scene order.
#include "harness/report/report_scene.hpp"

#include <cmath>
#include <variant>

#include "harness/report/report_contact.hpp"
#include "harness/report/report_format.hpp"
#include "harness/report/report_landing.hpp"
#include "harness/report/report_rotation.hpp"
#include "harness/report/report_summary.hpp"

namespace dropcheck {
namespace {

const char* kTimed = "⏱ ";  // marks the columns that hold wall-clock timings

std::string vec3(const Vec3& v) {
  return printf_string("(%g, %g, %g)", v.x(), v.y(), v.z());
}

std::string sweep_text(const SceneEvaluation& se) {
  std::string s;
  for (const Timestep& h : se.sweep) s += (s.empty() ? "" : ", ") + h.text;
  return s;
}

std::string bodies_text(const Scene& scene) {
  std::string s;
  for (const Body& b : scene.bodies) {
    s += s.empty() ? "" : "; ";
    if (b.is_static) {
      s += b.name + " (static, half extents " + vec3(b.half_extents) + " m, at " +
           vec3(b.position) + " m)";
    } else {
      s += b.name + printf_string(" (%g kg, half extents ", b.mass) + vec3(b.half_extents) +
           " m, from " + vec3(b.position) + " m at " + vec3(b.velocity) + " m/s)";
    }
  }
  return s;
}

std::string force_text(const Scene& scene, const Force& f) {
  std::string on;
  for (std::size_t i : f.bodies) on += (on.empty() ? "" : ", ") + scene.bodies[i].name;
  if (const auto* c = std::get_if<ConstantForce>(&f.law))
    return "constant " + vec3(c->force) + " N on " + on;
  const Spring& s = std::get<Spring>(f.law);
  return "spring to " + vec3(s.anchor) +
         printf_string(" m, stiffness %g N/m, damping %g N*s/m, rest length %g m on ", s.stiffness,
                       s.damping, s.rest_length) +
         on;
}

// What the scene leaves out, and therefore which metrics the section omits.
std::vector<std::string> left_out(const SceneEvaluation& se) {
  const Scene& s = se.scene;
  std::vector<std::string> out;
  if (!s.world.contacts) {
    bool statics = false;
    for (const Body& b : s.bodies) statics = statics || b.is_static;
    out.push_back(std::string("no contacts: no collision shapes created; contact metrics omitted") +
                  (statics ? " (static bodies are inert: the cubes fall through them)" : ""));
  } else {
    out.push_back(
        "the discrete laws model free flight only: with contacts, no own-law oracle, and "
        "divergences are attributed over the fall before first contact only");
  }
  if (!se.no_analytic.empty())
    out.push_back(
        "no closed form (" + se.no_analytic + "): analytic columns omitted" +
        (se.uses_fine ? "; errors are against the same engine at h = " + se.fine_step.text : ""));
  if (s.world.damping_rate == 0.0)
    out.push_back(
        "no damping (k = 0): every engine's law reduces to semi-implicit Euler, so damping "
        "order cannot split them");
  if (s.forces.empty()) out.push_back("no external forces");
  return out;
}

std::string scene_intro(const SceneEvaluation& se) {
  const Scene& s = se.scene;
  std::string md = s.description.empty() ? "" : s.description + "\n\n";
  md += "- File: `" + s.source + "`; " + sig(s.duration, 6) + " s" + " at h = " + s.timestep.text +
        printf_string(" (%lld steps)", static_cast<long long>(step_count(s, s.timestep.seconds))) +
        "; sweep " + sweep_text(se) + "; divergence tolerance " + length(s.tolerance) + ".\n";
  md += "- World: gravity " + vec3(s.world.gravity) +
        printf_string(" m/s^2; damping k = %.6g 1/s", s.world.damping_rate) +
        printf_string(" (phi = %.6g per step at h = ", decay_per_step(s, s.timestep.seconds)) +
        s.timestep.text + "); contacts " + (s.world.contacts ? "on" : "off") + ".\n";
  md += "- Bodies: " + bodies_text(s) + ".\n";
  for (const Force& f : s.forces) md += "- Force: " + force_text(s, f) + ".\n";
  for (const std::string& l : left_out(se)) md += "- Leaves out: " + l + ".\n";
  for (const EngineEvaluation& ev : se.engines)
    if (!ev.ran()) md += "- Not run: " + ev.name + " (" + ev.skipped + ").\n";
  return md + "\n";
}

std::string plot_md(const ReportPlot& plot, const PlotOutcomes& outcomes) {
  for (const auto& [file, why] : outcomes)
    if (file == plot.file)
      return why.empty() ? "![" + plot.alt + "](" + plot.file + ")\n\n"
                         : "(" + plot.alt + ": not drawn, " + why + ")\n\n";
  return {};
}

// Divergence from the reference at the default step, per engine and dynamic body.
std::string divergence_table(const SceneEvaluation& se) {
  MarkdownTable t({"engine", "body", "max dx (m)", "RMS dx (m)", "final dx (m)", "max dv (m/s)",
                   "RMS dv (m/s)", "final dv (m/s)", "dx > tolerance from t (s)"},
                  "llr");
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran() || ev.name == se.reference) continue;
    const StepEvaluation& st = ev.at_default();
    for (std::size_t b = 0; b < st.reference_by_body.size(); ++b) {
      if (se.scene.bodies[b].is_static) continue;
      const ErrorStats& e = st.reference_by_body[b];
      t.add({ev.name, se.scene.bodies[b].name, cell(e.max_dx), cell(e.rms_dx), cell(e.final_dx),
             cell(e.max_dv), cell(e.rms_dv), cell(e.final_dv), when(e.diverged_at)});
    }
  }
  return t.str();
}

std::string attribution_lines(const SceneEvaluation& se) {
  std::string md;
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran() || !ev.at_default().attribution) continue;
    const StepEvaluation& st = ev.at_default();
    const std::string until =
        st.attributed_until < 0.0
            ? ""
            : "Before first contact (t <= " + sig(st.attributed_until, 4) + " s): ";
    md += "- " + until + st.attribution->sentence() + " Cause: " + divergence_cause(se, ev) + ".\n";
  }
  return md.empty() ? md
                    : "Attribution (law part = what the two exact discrete laws predict; "
                      "residual = each engine's departure from its own law):\n\n" +
                          md + "\n";
}

std::string divergence(const SceneEvaluation& se, const std::vector<ReportPlot>& plots,
                       const PlotOutcomes& outcomes) {
  if (se.reference.empty()) return "No engine ran this scene.\n\n";
  std::string md =
      "#### Divergence from " + se.reference + " at h = " + se.scene.timestep.text + "\n\n";
  if (!se.reference_note.empty())
    md += "Reference: " + se.reference + ", because " + se.reference_note + ".\n\n";
  md += divergence_table(se) + "\n" + attribution_lines(se);
  for (const ReportPlot& p : plots)
    if (p.file.find("-divergence.svg") != std::string::npos) md += plot_md(p, outcomes);
  return md;
}

std::vector<std::string> oracle_header(const SceneEvaluation& se) {
  std::vector<std::string> h{"engine"};
  if (se.no_analytic.empty())
    h.insert(h.end(), {"closed form: max dx (m)", "final dx (m)", "max dv (m/s)"});
  if (se.uses_law)
    h.insert(h.end(), {"own law: max dx (m)", "max dv (m/s)", "rounding budget (m)", "within"});
  if (se.uses_fine)
    h.insert(h.end(),
             {"h = " + se.fine_step.text + ": max dx (m)", "final dx (m)", "max dv (m/s)"});
  return h;
}

std::vector<std::string> oracle_row(const EngineEvaluation& ev) {
  const StepEvaluation& st = ev.at_default();
  std::vector<std::string> r{ev.name};
  if (const auto& a = st.vs_analytic)
    r.insert(r.end(), {cell(a->max_dx), cell(a->final_dx), cell(a->max_dv)});
  if (const auto& l = st.vs_law) {
    const bool ok = st.own_law && st.own_law->follows();
    r.insert(r.end(),
             {cell(l->max_dx), cell(l->max_dv), cell(st.law_budget), ok ? "yes" : "**NO**"});
  }
  if (const auto& f = st.vs_fine)
    r.insert(r.end(), {cell(f->max_dx), cell(f->final_dx), cell(f->max_dv)});
  return r;
}

std::string oracles(const SceneEvaluation& se) {
  if (!se.no_analytic.empty() && !se.uses_law && !se.uses_fine) return {};
  MarkdownTable t(oracle_header(se), "lr");
  for (const EngineEvaluation& ev : se.engines)
    if (ev.ran()) t.add(oracle_row(ev));
  return "#### Error against each oracle at h = " + se.scene.timestep.text + " (worst body)\n\n" +
         t.str() + "\n";
}

std::vector<std::string> sweep_row(const SceneEvaluation& se, const StepEvaluation& st,
                                   bool timing) {
  std::string status = to_string(st.run.status);
  if (st.run.clamped_steps)
    status +=
        printf_string(", clamped on %lld steps", static_cast<long long>(st.run.clamped_steps));
  std::vector<std::string> r{st.h.text, std::to_string(st.run.steps), status,
                             cell(st.continuous_error())};
  if (!se.reference.empty()) r.push_back(st.vs_reference ? cell(st.vs_reference->max_dx) : kNone);
  if (!timing) return r;
  if (!st.timing) return r;
  const Timing& t = *st.timing;
  r.insert(r.end(), {cell(t.headline() * 1e3), cell(t.ratio()), cell(t.of(Statistic::median) * 1e3),
                     cell(statistic(t.full, Statistic::q25) * 1e3) + " .. " +
                         cell(quantile(t.full, 0.75) * 1e3),
                     cell(t.bare_of(Statistic::median) * 1e3), percent(t.overhead()),
                     printf_string("%d x %d x %d", t.samples(), t.replicas, t.repeats)});
  return r;
}

std::string sweep_table(const SceneEvaluation& se, bool timing) {
  const std::string ref = se.no_analytic.empty() ? "closed form" : "h = " + se.fine_step.text;
  std::vector<std::string> h{"engine", "h", "steps", "status", "error vs " + ref + ": max dx (m)"};
  if (!se.reference.empty()) h.push_back("divergence from " + se.reference + ": max dx (m)");
  if (timing)
    for (const char* c : {"min (ms per sim s)", "min / calibration", "median (ms per sim s)",
                          "IQR (ms per sim s)", "bare step loop median (ms per sim s)",
                          "harness overhead", "samples x replicas x repeats"})
      h.push_back(kTimed + std::string(c));
  MarkdownTable t(h, "llrlr");
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran()) continue;
    for (const StepEvaluation& st : ev.sweep) {
      std::vector<std::string> row{ev.name};
      for (std::string& c : sweep_row(se, st, timing)) row.push_back(std::move(c));
      t.add(std::move(row));
    }
  }
  return t.str();
}

std::string run_time(const SceneEvaluation& se, const std::vector<ReportPlot>& plots,
                     const PlotOutcomes& outcomes, bool timing) {
  std::string md =
      timing ? "#### Error against run time (⏱ wall time)\n\n" : "#### Error against run time\n\n";
  md += timing ? "Columns marked ⏱ and the work-precision plot are wall-clock timings (the only "
                 "figures that change between runs). The minimum is the headline; \"min / "
                 "calibration\" divides it by the minimum of the calibration loop timed in the "
                 "same rounds, a ratio to compare across machines (Timing reproducibility).\n\n"
               : "Timings omitted (--no-timing).\n\n";
  md += sweep_table(se, timing) + "\n";
  for (const ReportPlot& p : plots)
    if (p.file.find("-work-precision.svg") != std::string::npos) md += plot_md(p, outcomes);
  return md;
}

std::string orders_table(const SceneEvaluation& se) {
  const bool cont = se.no_analytic.empty() || se.uses_fine;
  if (se.sweep.size() < 2 || (!cont && se.reference.empty())) return {};
  std::vector<std::string> h{"engine"};
  std::vector<std::string> steps;
  for (std::size_t i = 0; i + 1 < se.sweep.size(); ++i)
    steps.push_back(se.sweep[i].text + " → " + se.sweep[i + 1].text);
  const std::string ref = se.no_analytic.empty() ? "closed form" : "h = " + se.fine_step.text;
  if (cont)
    for (const std::string& s : steps) h.push_back("error vs " + ref + ", " + s);
  if (!se.reference.empty())
    for (const std::string& s : steps) h.push_back("divergence from " + se.reference + ", " + s);
  MarkdownTable t(h, "lr");
  for (const EngineEvaluation& ev : se.engines) {
    if (!ev.ran()) continue;
    std::vector<std::string> r{ev.name};
    if (cont)
      for (std::size_t i = 0; i < steps.size(); ++i)
        r.push_back(i < ev.orders_continuous.size() ? order(ev.orders_continuous[i]) : kNone);
    if (!se.reference.empty())
      for (std::size_t i = 0; i < steps.size(); ++i)
        r.push_back(i < ev.orders_reference.size() ? order(ev.orders_reference[i]) : kNone);
    t.add(std::move(r));
  }
  return "#### Observed order of convergence\n\np = ln(e1/e2) / ln(h1/h2) between "
         "consecutive steps of the sweep (1 = first order: the error halves with h; 4 = fourth "
         "order, "
         "RK4: it falls 16-fold; — where "
         "an error is zero, or a divergence is within the two engines' rounding budget).\n\n" +
         t.str() + "\n";
}

std::string failures(const SceneEvaluation& se) {
  std::string md;
  for (const EngineEvaluation& ev : se.engines) {
    for (const StepEvaluation& st : ev.sweep) {
      if (st.run.status != RunStatus::ok)
        md += "- " + ev.name + " at h = " + st.h.text + ": " + to_string(st.run.status) +
              " at step " + std::to_string(st.run.failed_step) + ": " + st.run.failure + ".\n";
      if (st.run.clamped_steps)
        md += "- " + ev.name + " at h = " + st.h.text +
              printf_string(": speed clamped on %lld steps, first at step %lld.\n",
                            static_cast<long long>(st.run.clamped_steps),
                            static_cast<long long>(st.run.first_clamped_step));
    }
    if (se.uses_fine && ev.ran() && ev.fine.status != RunStatus::ok)
      md += "- " + ev.name + " at the fine step h = " + se.fine_step.text + ": " + ev.fine.failure +
            ".\n";
  }
  return md.empty() ? md : "#### Failures (recorded, not dropped)\n\n" + md + "\n";
}

}  // namespace

std::string heading_anchor(const std::string& heading) {
  std::string a;
  for (char c : heading) {
    if (c >= 'A' && c <= 'Z')
      a += static_cast<char>(c - 'A' + 'a');
    else if ((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_')
      a += c;
    else if (c == ' ')
      a += '-';
  }
  return a;
}

std::string scene_section(const SceneEvaluation& se, const std::vector<ReportPlot>& plots,
                          const PlotOutcomes& outcomes, bool timing) {
  std::string md = "### " + se.scene.name + "\n\n" + scene_intro(se);
  for (const ReportPlot& p : plots)
    if (p.file.find("-trajectory.svg") != std::string::npos) md += plot_md(p, outcomes);
  // A slide, a bounce or a stack has its own table; the landing table follows where other bodies
  // land (as `dropcheck check` judges them).
  const std::string contact = slide_section(se) + bounce_section(se) + stack_section(se);
  bool lands = false;
  for (const EngineEvaluation& ev : se.engines)
    lands = lands || (ev.ran() && !ev.at_default().landings.empty());
  md += failures(se) + contact + (contact.empty() || lands ? landing_section(se) : "") +
        rotation_section(se) + divergence(se, plots, outcomes) + oracles(se) +
        run_time(se, plots, outcomes, timing);
  return md + orders_table(se);
}

}  // namespace dropcheck
