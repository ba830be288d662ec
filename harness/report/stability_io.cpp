// A stability study out: JSON for scripts (exact numbers) and a plain-text table for people.
#include "harness/report/stability_io.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "harness/core/number_format.hpp"
#include "harness/io/json_text.hpp"
#include "harness/io/trajectory_io.hpp"
#include "harness/study/stability_study.hpp"

namespace dropcheck {
namespace {

using Json = nlohmann::ordered_json;

// JSON has no NaN or Inf: null for them (and for an absent value).
Json json_number(std::optional<double> v) {
  return v && std::isfinite(*v) ? Json(*v) : Json(nullptr);
}

Json failures_json(const Verdict& v) {
  Json out = Json::array();
  for (const Failure& f : v.failures)
    out.push_back(
        {{"mode", to_string(f.mode)}, {"body", f.body}, {"step", f.step}, {"message", f.what}});
  return out;
}

void add_search(Json& out, const std::optional<StepSearch>& s) {
  if (!s) {
    out["max_stable_dt"] = nullptr;
    out["search"] = nullptr;
    return;
  }
  out["max_stable_dt"] = json_number(s->max_stable_dt);
  out["search"] = {{"min_unstable_dt", json_number(s->min_unstable_dt)},
                   {"min_stable_dt", json_number(s->min_stable_dt)},
                   {"limit", s->limit ? Json(to_string(*s->limit)) : Json(nullptr)},
                   {"capped", std::isnan(s->min_unstable_dt) && !std::isnan(s->max_stable_dt)},
                   {"start", json_number(s->start)},
                   {"cap", json_number(s->cap)},
                   {"horizon", json_number(s->horizon)},
                   {"probes", s->probes}};
}

Json engine_json(const EngineStability& e) {
  Json out = {{"engine", e.engine}};
  if (!e.ran()) {
    out["skipped"] = e.skipped;
    return out;
  }
  out["scalar"] = to_string(e.scalar);
  out["law"] = to_string(e.law);
  out["status"] = to_string(e.status);
  out["steps_run"] = e.steps_run;
  out["verdict"] = e.verdict.stable() ? "stable" : to_string(e.verdict.failures.front().mode);
  out["failures"] = failures_json(e.verdict);
  out["error_vs_analytic"] = nullptr;
  if (e.vs_analytic)
    out["error_vs_analytic"] = {{"max_dx", json_number(e.vs_analytic->max_dx)},
                                {"final_dx", json_number(e.vs_analytic->final_dx)},
                                {"max_dv", json_number(e.vs_analytic->max_dv)}};
  add_search(out, e.search);
  out["theory_max_dt"] = json_number(e.theory_max_dt);
  return out;
}

// "0.0333333" or "-" for a value that is absent.
std::string cell(std::optional<double> v, const char* pattern = "%.6g") {
  return v && std::isfinite(*v) ? printf_string(pattern, *v) : std::string("-");
}

}  // namespace

std::string search_summary(const StepSearch& s) {
  std::string out;
  if (!std::isnan(s.min_stable_dt)) out = printf_string("frozen below %.4g s; ", s.min_stable_dt);
  if (std::isnan(s.max_stable_dt) && std::isnan(s.min_unstable_dt))  // rise() found no stable h
    return out + printf_string("frozen at every h tried, from %.4g s up to the cap %.4g s", s.start,
                               s.cap);
  if (std::isnan(s.max_stable_dt))
    return out + printf_string("%s at every h tried, from %.4g s down to %.4g s",
                               s.limit ? to_string(*s.limit) : "fails", s.start, s.min_unstable_dt);
  if (std::isnan(s.min_unstable_dt))
    return out + printf_string("no failure up to the cap %.4g s", s.cap);
  return out + printf_string("fails at %.6g s (%s)", s.min_unstable_dt,
                             s.limit ? to_string(*s.limit) : "?");
}

std::string stability_to_json(const SceneStability& s, const SearchOptions& search) {
  const Json head = {
      {"scene", s.name},
      {"file", s.source},
      {"dt", s.h.seconds},
      {"dt_text", s.h.text},
      {"duration", s.duration},
      {"steps", s.steps},
      {"no_analytic", s.no_analytic},
      {"search_rule",
       printf_string("each probe at step h runs duration' = ceil(min(duration, %lld*dt)/h)*h; "
                     "bisection to a relative %.3g",
                     static_cast<long long>(search.horizon_steps), search.rel_tol)}};
  std::string out = json_line(head);  // then the engines, one a line, as before nlohmann wrote them
  out.pop_back();
  out += ",\"engines\":[";
  for (std::size_t i = 0; i < s.engines.size(); ++i)
    out += (i ? ",\n" : "\n") + json_line(engine_json(s.engines[i]));
  return out + "\n]}\n";
}

std::string stability_to_text(const SceneStability& s) {
  std::string out =
      printf_string("scene %s: h = %s (%lld steps over %g s); analytic oracle: %s\n",
                    s.name.c_str(), s.h.text.c_str(), static_cast<long long>(s.steps), s.duration,
                    s.no_analytic.empty() ? "yes" : s.no_analytic.c_str());
  out += printf_string("%-16s %-17s %-14s %-14s %-12s %s\n", "engine", "at h", "max stable h",
                       "theory h", "max |dx| m", "search");
  std::string sentences;
  for (const EngineStability& e : s.engines) {
    if (!e.ran()) {
      out += printf_string("%-16s skipped: %s\n", e.engine.c_str(), e.skipped.c_str());
      continue;
    }
    const std::string verdict =
        e.verdict.stable() ? "stable" : to_string(e.verdict.failures.front().mode);
    const std::string search = e.search ? search_summary(*e.search) : "-";
    out += printf_string(
        "%-16s %-17s %-14s %-14s %-12s %s\n", e.label().c_str(), verdict.c_str(),
        cell(e.search ? std::optional(e.search->max_stable_dt) : std::nullopt).c_str(),
        cell(e.theory_max_dt).c_str(),
        cell(e.vs_analytic ? std::optional(e.vs_analytic->max_dx) : std::nullopt, "%.3g").c_str(),
        search.c_str());
    for (const Failure& f : e.verdict.failures)
      sentences += "  " + e.label() + ": " + f.what + "\n";
  }
  return out + sentences;
}

}  // namespace dropcheck
