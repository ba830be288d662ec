// A stability study out: JSON for scripts (exact numbers) and a plain-text table for people.
#include <algorithm>
#include <cmath>

#include "harness/stability/stability_detail.hpp"
#include "harness/stability/stability_study.hpp"
#include "harness/core/trajectory_io.hpp"

namespace dropcheck {
namespace {

using stability_detail::format;

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      out += format("\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      continue;
    }
    out += c;
  }
  return out + "\"";
}

// JSON has no NaN or Inf: null for them (and for an absent value).
std::string json_number(std::optional<double> v) {
  return v && std::isfinite(*v) ? exact(*v) : "null";
}

std::string failures_json(const Verdict& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.failures.size(); ++i) {
    const Failure& f = v.failures[i];
    out += (i ? ",{" : "{") + std::string("\"mode\":") + json_string(to_string(f.mode)) +
           ",\"body\":" + json_string(f.body) + ",\"step\":" + std::to_string(f.step) +
           ",\"message\":" + json_string(f.what) + "}";
  }
  return out + "]";
}

std::string search_json(const std::optional<StepSearch>& s) {
  if (!s) return "\"max_stable_dt\":null,\"search\":null";
  return "\"max_stable_dt\":" + json_number(s->max_stable_dt) + ",\"search\":{" +
         "\"min_unstable_dt\":" + json_number(s->min_unstable_dt) +
         ",\"min_stable_dt\":" + json_number(s->min_stable_dt) +
         ",\"limit\":" + (s->limit ? json_string(to_string(*s->limit)) : std::string("null")) +
         ",\"capped\":" +
         (std::isnan(s->min_unstable_dt) && !std::isnan(s->max_stable_dt) ? "true" : "false") +
         ",\"start\":" + json_number(s->start) + ",\"cap\":" + json_number(s->cap) +
         ",\"horizon\":" + json_number(s->horizon) + ",\"probes\":" + std::to_string(s->probes) +
         "}";
}

std::string engine_json(const EngineStability& e) {
  std::string out = "{\"engine\":" + json_string(e.engine);
  if (!e.ran()) return out + ",\"skipped\":" + json_string(e.skipped) + "}";
  out += ",\"scalar\":" + json_string(to_string(e.scalar)) +
         ",\"law\":" + json_string(to_string(e.law)) +
         ",\"status\":" + json_string(to_string(e.status)) +
         ",\"steps_run\":" + std::to_string(e.steps_run) + ",\"verdict\":" +
         json_string(e.verdict.stable() ? "stable" : to_string(e.verdict.failures.front().mode)) +
         ",\"failures\":" + failures_json(e.verdict) + ",\"error_vs_analytic\":";
  if (e.vs_analytic)
    out += "{\"max_dx\":" + json_number(e.vs_analytic->max_dx) +
           ",\"final_dx\":" + json_number(e.vs_analytic->final_dx) +
           ",\"max_dv\":" + json_number(e.vs_analytic->max_dv) + "}";
  else
    out += "null";
  return out + "," + search_json(e.search) + ",\"theory_max_dt\":" + json_number(e.theory_max_dt) +
         "}";
}

// "0.0333333" or "-" for a value that is absent.
std::string cell(std::optional<double> v, const char* pattern = "%.6g") {
  return v && std::isfinite(*v) ? format(pattern, *v) : std::string("-");
}

}  // namespace

std::string search_summary(const StepSearch& s) {
  std::string out;
  if (!std::isnan(s.min_stable_dt)) out = format("frozen below %.4g s; ", s.min_stable_dt);
  if (std::isnan(s.max_stable_dt) && std::isnan(s.min_unstable_dt))  // rise() found no stable h
    return out +
           format("frozen at every h tried, from %.4g s up to the cap %.4g s", s.start, s.cap);
  if (std::isnan(s.max_stable_dt))
    return out + format("%s at every h tried, from %.4g s down to %.4g s",
                        s.limit ? to_string(*s.limit) : "fails", s.start, s.min_unstable_dt);
  if (std::isnan(s.min_unstable_dt)) return out + format("no failure up to the cap %.4g s", s.cap);
  return out +
         format("fails at %.6g s (%s)", s.min_unstable_dt, s.limit ? to_string(*s.limit) : "?");
}

std::string stability_to_json(const SceneStability& s, const SearchOptions& search) {
  std::string out =
      "{\"scene\":" + json_string(s.name) + ",\"file\":" + json_string(s.source) +
      ",\"dt\":" + exact(s.h.seconds) + ",\"dt_text\":" + json_string(s.h.text) +
      ",\"duration\":" + exact(s.duration) + ",\"steps\":" + std::to_string(s.steps) +
      ",\"no_analytic\":" + json_string(s.no_analytic) + ",\"search_rule\":" +
      json_string(format("each probe at step h runs duration' = ceil(min(duration, %lld*dt)/h)*h; "
                         "bisection to a relative %.3g",
                         static_cast<long long>(search.horizon_steps), search.rel_tol)) +
      ",\"engines\":[";
  for (std::size_t i = 0; i < s.engines.size(); ++i)
    out += (i ? ",\n" : "\n") + engine_json(s.engines[i]);
  return out + "\n]}\n";
}

std::string stability_to_text(const SceneStability& s) {
  std::string out = format("scene %s: h = %s (%lld steps over %g s); analytic oracle: %s\n",
                           s.name.c_str(), s.h.text.c_str(), static_cast<long long>(s.steps),
                           s.duration, s.no_analytic.empty() ? "yes" : s.no_analytic.c_str());
  out += format("%-16s %-17s %-14s %-14s %-12s %s\n", "engine", "at h", "max stable h", "theory h",
                "max |dx| m", "search");
  std::string sentences;
  for (const EngineStability& e : s.engines) {
    if (!e.ran()) {
      out += format("%-16s skipped: %s\n", e.engine.c_str(), e.skipped.c_str());
      continue;
    }
    const std::string verdict =
        e.verdict.stable() ? "stable" : to_string(e.verdict.failures.front().mode);
    const std::string search = e.search ? search_summary(*e.search) : "-";
    out += format(
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
