// The stability section of the report (Markdown). Every number is printed with a fixed format so
// that the section is byte-stable for a given build; wall times never appear.
#include "harness/report/stability_report.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "harness/core/number_format.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/stability_study.hpp"

namespace dropcheck {
namespace {

// A Markdown table row from cells.
std::string row(const std::vector<std::string>& cells) {
  std::string out = "|";
  for (const std::string& c : cells) out += " " + c + " |";
  return out + "\n";
}

// Header row, then the separator; the first two columns left-aligned, the engines right-aligned.
std::string header(const std::vector<std::string>& first, const std::vector<std::string>& engines,
                   bool right_align_rest) {
  std::vector<std::string> cells = first;
  for (const std::string& e : engines) cells.push_back(e);
  std::string out = row(cells) + "|";
  for (std::size_t i = 0; i < cells.size(); ++i)
    out += i >= first.size() && right_align_rest ? "---:|" : "---|";
  return out + "\n";
}

// The study's entry for engine `name`, or nullptr.
const EngineStability* find(const SceneStability& s, const std::string& name) {
  for (const EngineStability& e : s.engines)
    if (e.engine == name) return &e;
  return nullptr;
}

std::string skipped_cell(const EngineStability* e) {
  if (!e) return "-";
  return e->skipped.rfind("not compiled", 0) == 0 ? "not built" : e->skipped;
}

std::string verdict_cell(const EngineStability* e) {
  if (!e || !e->ran()) return skipped_cell(e);
  return e->verdict.stable() ? "stable"
                             : printf_string("**%s**", to_string(e->verdict.failures.front().mode));
}

std::string step_cell(const EngineStability* e) {
  if (!e || !e->ran()) return skipped_cell(e);
  if (!e->search) return "-";
  const StepSearch& s = *e->search;
  std::string out;
  if (std::isnan(s.max_stable_dt))
    out = printf_string("none (%s)", s.limit ? to_string(*s.limit) : "fails");
  else if (std::isnan(s.min_unstable_dt))
    out = printf_string(">= %.4g (cap)", s.max_stable_dt);
  else
    out = printf_string("%.4g (%s)", s.max_stable_dt, s.limit ? to_string(*s.limit) : "?");
  if (e->theory_max_dt) out += printf_string(" / %.4g", *e->theory_max_dt);
  return out;
}

std::string analytic_error_cell(const EngineStability* e) {
  if (!e || !e->ran()) return skipped_cell(e);
  return e->vs_analytic ? printf_string("%.2e", e->vs_analytic->max_dx) : std::string("-");
}

template <typename Cell>
std::string table(const std::vector<SceneStability>& studies, Cell cell, bool with_step) {
  // The engines passed in, in their order: every study has the same list.
  std::vector<std::string> engines;
  if (!studies.empty())
    for (const EngineStability& e : studies.front().engines) engines.push_back(e.engine);
  std::string out =
      with_step ? header({"scene", "h"}, engines, true) : header({"scene"}, engines, true);
  for (const SceneStability& s : studies) {
    std::vector<std::string> cells{"`" + s.name + "`"};
    if (with_step) cells.push_back(s.h.text);
    for (const std::string& name : engines) cells.push_back(cell(find(s, name)));
    out += row(cells);
  }
  return out;
}

std::string scene_list(const std::vector<SceneStability>& studies) {
  std::string out;
  for (const SceneStability& s : studies) {
    std::string d = s.description;
    std::replace(d.begin(), d.end(), '\n', ' ');
    out += printf_string("- `%s` (%s, %lld steps of %s s): ", s.name.c_str(),
                         std::filesystem::path(s.source).filename().string().c_str(),
                         static_cast<long long>(s.steps), s.h.text.c_str()) +
           d + "\n";
  }
  return out;
}

std::string failure_list(const std::vector<SceneStability>& studies) {
  std::string out;
  for (const SceneStability& s : studies)
    for (const EngineStability& e : s.engines)
      for (const Failure& f : e.verdict.failures)
        out +=
            "- `" + s.name + "`, " + e.label() + ", " + to_string(f.mode) + ": " + f.what + ".\n";
  return out.empty() ? "No failure at any scene's own step.\n" : out;
}

}  // namespace

std::string stability_report_section(const std::vector<std::string>& extreme_scene_files,
                                     const std::vector<EngineSlot>& engines,
                                     std::ostream& progress) {
  std::vector<Scene> scenes;
  for (const std::string& file : extreme_scene_files) scenes.push_back(load_scene(file));
  std::sort(scenes.begin(), scenes.end(),
            [](const Scene& a, const Scene& b) { return a.name < b.name; });
  const StudyOptions options;
  std::vector<SceneStability> studies;
  for (const Scene& scene : scenes)
    studies.push_back(study_scene(scene, engines, options, &progress));

  const SearchOptions& so = options.search_options;
  std::string out = "## Stability: stiff and extreme cases\n\n";
  out += printf_string(
      "Each engine runs each scene at the scene's own step h and is classified as stable or by its "
      "severest failure (NaN/Inf, engine error, unbounded growth, tunnelled, frozen, speed "
      "clamped, or off contact law: a slide, bounce or stack that leaves its engine's contact law "
      "as `dropcheck check` judges it; harness/judge/stability_classify.hpp). Then its largest "
      "stable "
      "step is searched by bisection on "
      "h: each "
      "probe "
      "runs min(duration, %lld h) rounded up to whole steps of the probe's h, and the bisection "
      "stops "
      "at a relative width of %.1g. For springs the theoretical edge of the engine's damping order "
      "follows the measured one (harness/oracles/stability_theory.cpp): semi-implicit Euler "
      "without "
      "damping is "
      "stable iff omega*h < 2.\n\n",
      static_cast<long long>(so.horizon_steps), so.rel_tol);
  out += "### Scenes\n\n" + scene_list(studies);
  out += "\n### Verdict at each scene's step\n\n" + table(studies, verdict_cell, true);
  out +=
      "\n### Largest stable step h (s): measured (what failed above it) / theory for springs\n\n" +
      table(studies, step_cell, false);
  out += "\n### Error at the scene's step against the analytic solution: max |dx| (m)\n\n" +
         table(studies, analytic_error_cell, false);
  out += "\n### What failed at each scene's step\n\n" + failure_list(studies);
  return out;
}

}  // namespace dropcheck
