#include "harness/plan/cell_record.hpp"

#include <unistd.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "harness/core/build_id.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/provenance.hpp"
#include "harness/core/registry.hpp"
#include "harness/core/rotation_law.hpp"
#include "harness/core/trajectory_hash.hpp"
#include "harness/io/json_text.hpp"
#include "harness/judge/law_stability.hpp"
#include "harness/judge/metrics.hpp"
#include "harness/judge/own_law.hpp"
#include "harness/oracles/analytic.hpp"
#include "harness/oracles/stability_theory.hpp"
#include "harness/plan/axes.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {
namespace {

using Json = nlohmann::ordered_json;

// A number; Inf and NaN as the strings "inf", "-inf", "nan" (JSON has no such numbers).
Json number(double v) {
  if (std::isfinite(v)) return v;
  return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf";
}

Json record_engine_json(const EngineInfo& i) {
  Json e{{"name", i.name},
         {"version", i.version},
         {"scalar", to_string(i.scalar)},
         {"law", law_key(i.law)}};
  if (i.capabilities.rotation != Rotation::none)
    e["rotation_law"] = rotation_law_key(i.rotation_law);
  if (i.accuracy > 0.0) e["accuracy"] = i.accuracy;
  e["settings"] = i.damping_mapping;
  if (!i.contact_settings.empty()) e["contact_settings"] = i.contact_settings;
  return e;
}

std::string host_name() {
  char name[256] = {};
  return gethostname(name, sizeof name - 1) == 0 ? std::string(name) : std::string("unknown");
}

void measure_error(const Scene& scene, const Trajectory& run, Json& r) {
  if (const std::string why = analytic_unavailable(scene); !why.empty()) {
    r["error"] = {{"closed_form", nullptr}, {"why_none", why}};
    return;
  }
  const ErrorStats e = compare_worst(run, *analytic_trajectory(scene, run.h), 0.0);
  r["error"] = {{"closed_form", {{"max_dx", number(e.max_dx)}, {"max_dv", number(e.max_dv)}}}};
}

void measure_own_law(const EngineInfo& info, const Scene& scene, const Trajectory& run, Json& r) {
  if (scene.world.contacts) {
    r["own_law"] = {{"judged", false}, {"why_not", "contacts: the law family is free flight"}};
    return;
  }
  const OwnLawVerdict v = judge_own_law(info, scene, run);
  r["own_law"] = {{"judged", true},
                  {"follows", v.follows()},
                  {"residual_x", number(v.residual_x)},
                  {"residual_v", number(v.residual_v)},
                  {"tolerance_x", number(v.tolerance.x)},
                  {"tolerance_v", number(v.tolerance.v)}};
}

void measure_stability(const EngineInfo& info, const Scene& scene, const Timestep& h,
                       const Trajectory& run, Json& r) {
  const std::optional<double> edge = theory_max_dt(scene, info.law);
  r["stability"] = {{"stable", run.status == RunStatus::ok},
                    {"law_unstable", law_instability(scene, info.law, h)},
                    {"theory_max_h", edge ? number(*edge) : Json(nullptr)}};
}

void measure_timing(const Scene& scene, const Trajectory& run, Json& r) {
  std::size_t dynamic = 0;
  for (const Body& b : scene.bodies) dynamic += b.is_static ? 0 : 1;
  const double body_steps = static_cast<double>(run.steps) * static_cast<double>(dynamic);
  r["timing"] = {{"wall_time", true},
                 {"ns_per_body_step", number(run.wall_seconds * 1e9 / std::max(body_steps, 1.0))},
                 {"cpu", cpu_model()},
                 {"host", host_name()}};
}

CellRecord finish(Json& r, const std::string& status, const std::string& reason) {
  r["status"] = status;
  if (!reason.empty()) r["reason"] = reason;
  return {status, json_text(r)};
}

Json build_json() {
  const BuildId build = current_build();
  return {{"key", build.key}, {"flags", build.flags}, {"commit", source_commit()}};
}

}  // namespace

std::string cell_identity(const Plan& plan, const Cell& cell) {
  std::string id = cell.key + "\n" + plan.scenes[cell.scene].text + "\n";
  for (Measure m : plan.measures) id += std::string(to_string(m)) + ",";
  return fnv1a_hex(id + "\n" + json_text(build_json()));
}

CellRecord adopt_record(const Plan& plan, const Cell& cell, const std::string& line) {
  Json r;
  try {
    r = parse_json<Json>(line);
  } catch (const std::exception&) {
    return {};
  }
  if (!r.is_object() || r.value("format", "") != kRecordFormat || r.value("key", "") != cell.key ||
      !r.contains("build") || r["build"] != build_json() || !r.contains("status") ||
      !r["status"].is_string())
    return {};
  r["plan"] = plan.hash;
  return {r["status"].get<std::string>(), json_text(r)};
}

CellRecord run_cell(const Plan& plan, const Cell& cell, Isolation isolation,
                    double time_limit_seconds) {
  Json r;
  r["format"] = kRecordFormat;
  r["key"] = cell.key;
  r["plan"] = plan.hash;
  r["build"] = build_json();
  const PlanScene& ps = plan.scenes[cell.scene];
  r["scene"] = ps.name;
  Json axes = Json::object();
  std::vector<std::string> values;
  for (std::size_t k = 0; k < plan.axes.size(); ++k) {
    values.push_back(plan.axes[k].values[cell.values[k]]);
    axes[plan.axes[k].name] = values.back();
  }
  r["axes"] = axes;
  CellSetup c;
  try {
    c = setup_cell(ps.text, ps.file, plan.engines[cell.engine], plan.axes, values);
  } catch (const InputError& e) {
    return finish(r, "invalid", e.what());
  }
  // An external engine starts as `sweep --engine-file` named it; a scalar axis may have turned ours
  // into ours-f64.
  const std::string start =
      c.engine == plan.engines[cell.engine] ? plan.runs(cell.engine) : c.engine;
  std::unique_ptr<Engine> engine;
  try {
    engine = start.empty() ? nullptr : make_engine(start);
  } catch (const InputError& e) {  // an engine file gone or broken since the sweep began
    return finish(r, "engine-error", e.what());
  }
  if (!engine)
    return finish(r, "skipped",
                  c.engine + ": " +
                      (start.empty() ? "an external engine not given to `sweep --engine-file`"
                                     : engine_unavailable_reason(start)));
  const EngineInfo info = engine->info();
  r["engine"] = record_engine_json(info);
  // An external engine is named as its cells are (NAME@FP): two versions of it never pool.
  if (start != c.engine) r["engine"]["name"] = c.engine;
  r["h"] = c.h.text;
  r["steps"] = step_count(c.scene, c.h.seconds);
  if (!c.scalar.empty() && c.scalar != to_string(info.scalar))
    return finish(r, "skipped", info.name + " runs in " + to_string(info.scalar) + " only");
  if (const std::string why = engine->cannot_run(c.scene); !why.empty())
    return finish(r, "skipped", why);
  RunOptions options;
  options.isolation = isolation;
  options.time_limit_seconds = time_limit_seconds;
  const Trajectory run = run_scene(*engine, c.scene, c.h.seconds, options);
  const std::string status = status_key(run.status);
  r["status"] = status;
  if (run.status == RunStatus::timed_out) {
    // How far a run got before its wall-clock limit depends on the machine: the record keeps the
    // limit and leaves out the step and every measure of the samples it reached, so it stays the
    // same bytes on every run.
    r["reason"] = run.failure.substr(0, run.failure.find(';'));
    return {status, json_text(r)};
  }
  if (run.status == RunStatus::refused) {  // over a run limit: nothing ran, nothing to measure
    r["reason"] = run.failure;
    return {status, json_text(r)};
  }
  if (run.status != RunStatus::ok) {
    r["reason"] = run.failure;
    r["failed_step"] = run.failed_step;
  }
  if (plan.has(Measure::error)) measure_error(c.scene, run, r);
  if (plan.has(Measure::own_law)) measure_own_law(info, c.scene, run, r);
  if (plan.has(Measure::stability)) measure_stability(info, c.scene, c.h, run, r);
  if (plan.has(Measure::hash)) r["hash"] = trajectory_hash_hex(run);
  if (plan.has(Measure::timing)) measure_timing(c.scene, run, r);
  return {status, json_text(r)};
}

}  // namespace dropcheck
