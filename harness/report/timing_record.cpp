#include "harness/report/timing_record.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <tuple>

#include "harness/core/engine_listing.hpp"
#include "harness/core/input_error.hpp"
#include "harness/io/bounded_read.hpp"
#include "harness/io/json_text.hpp"

namespace dropcheck {
namespace {

using Json = nlohmann::ordered_json;

std::vector<double> in_ms(const std::vector<double>& seconds) {
  std::vector<double> out;
  for (double s : seconds) out.push_back(1e3 * s);
  return out;
}

TimedCell timed_cell(const std::string& scene, const std::string& engine,
                     const StepEvaluation& st) {
  const Timing& t = *st.timing;
  return {scene,      engine,   st.h.text, in_ms(t.full), in_ms(t.bare), in_ms(t.calibration),
          t.replicas, t.repeats};
}

// The samples are the record; the headline, ratio and median beside them are for a reader of the
// file, and are derived again from the samples when it is read.
Json cell_json(const TimedCell& c) {
  return {{"scene", c.scene},
          {"engine", c.engine},
          {"h", c.h},
          {"headline_ms", c.value({})},
          {"ratio", c.value({kHeadline, true})},
          {"median_ms", c.value({Statistic::median, false})},
          {"replicas", c.replicas},
          {"repeats", c.repeats},
          {"samples_ms", c.full_ms},
          {"bare_samples_ms", c.bare_ms},
          {"calibration_ms", c.calibration_ms}};
}

// Reads the typed values of a parsed record, naming the key of the first that is wrong.
struct JsonReader {
  const std::string& file;

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw InputError(file, 0, key, problem);
  }
  const Json& at(const Json& object, const std::string& key, const std::string& where) const {
    const auto it = object.find(key);
    if (it == object.end()) fail(where + key, "required key is missing");
    return *it;
  }
  std::string text(const Json& object, const std::string& key, const std::string& where) const {
    const Json& v = at(object, key, where);
    if (!v.is_string()) fail(where + key, std::string("expected a string, got ") + v.type_name());
    const std::string s = v.get<std::string>();
    // Printed into the report and on terminals: short and inert, as dropcheck writes them.
    if (s.size() > 256 || find_unsafe_in_line(s) != std::string::npos)
      fail(where + key, "expected a short text without control characters, got " + excerpt(s));
    return s;
  }
  double number(const Json& object, const std::string& key, const std::string& where) const {
    const Json& v = at(object, key, where);
    if (!v.is_number()) fail(where + key, std::string("expected a number, got ") + v.type_name());
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < 0) fail(where + key, "expected a finite number >= 0");
    return x;
  }
  // `positive`: a time that is a divisor (an engine's sample, a calibration) must be > 0; a bare
  // loop that could not load is 0.
  std::vector<double> samples(const Json& object, const std::string& key, const std::string& where,
                              bool positive = true) const {
    const Json& v = at(object, key, where);
    if (!v.is_array() || v.empty() || v.size() > 4096)
      fail(where + key, "expected an array of 1 to 4096 numbers");
    std::vector<double> out;
    for (std::size_t i = 0; i < v.size(); ++i) {
      out.push_back(number(v, i, where + key));
      if (positive && !(out.back() > 0.0))
        fail(where + key + "[" + std::to_string(i) + "]", "expected a time > 0");
    }
    return out;
  }
  double number(const Json& array, std::size_t i, const std::string& key) const {
    const Json& v = array[i];
    const std::string at_i = key + "[" + std::to_string(i) + "]";
    if (!v.is_number()) fail(at_i, std::string("expected a number, got ") + v.type_name());
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < 0) fail(at_i, "expected a finite number >= 0");
    return x;
  }
  int count(const Json& object, const std::string& key, const std::string& where) const {
    const Json& v = at(object, key, where);
    if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > 1 << 30)
      fail(where + key, "expected a whole number from 1 to 2^30");
    return v.get<int>();
  }
  // The machine object (a record from before dropcheck wrote one has none: an unknown machine).
  Machine machine(const Json& m) const {
    if (!m.is_object()) fail("machine", std::string("expected an object, got ") + m.type_name());
    Machine out{text(m, "cpu", "machine."),    text(m, "cpu_id", "machine."),
                text(m, "caches", "machine."), 0,
                text(m, "kernel", "machine."), text(m, "installation", "machine.")};
    const Json& cpus = at(m, "logical_cpus", "machine.");
    if (!cpus.is_number_integer() || cpus.get<long long>() < 0 || cpus.get<long long>() > 1 << 20)
      fail("machine.logical_cpus", "expected a whole number from 0 to 2^20");
    out.logical_cpus = cpus.get<int>();
    return out;
  }
  TimedCell cell(const Json& c, const std::string& name) const {
    if (!c.is_object()) fail(name, std::string("expected an object, got ") + c.type_name());
    const std::string where = name + ".";
    if (c.contains("median_ms") && !c.contains("samples_ms"))
      fail(name, "written by an older dropcheck, which kept no samples: write the report again");
    TimedCell out{text(c, "scene", where),
                  text(c, "engine", where),
                  text(c, "h", where),
                  samples(c, "samples_ms", where),
                  samples(c, "bare_samples_ms", where, false),
                  samples(c, "calibration_ms", where),
                  count(c, "replicas", where),
                  count(c, "repeats", where)};
    if (out.bare_ms.size() != out.full_ms.size() || out.calibration_ms.size() != out.full_ms.size())
      fail(where + "samples_ms", "samples_ms, bare_samples_ms and calibration_ms differ in length");
    return out;
  }
};

using Key = std::tuple<std::string, std::string, std::string>;

// The cells of `record` by key; a key found twice maps to nullptr (ambiguous: left out).
std::map<Key, const TimedCell*> by_key(const TimingRecord& record) {
  std::map<Key, const TimedCell*> out;
  for (const TimedCell& c : record.cells) {
    const auto [it, fresh] = out.emplace(Key{c.scene, c.engine, c.h}, &c);
    if (!fresh) it->second = nullptr;
  }
  return out;
}

// max/min - 1 of two figures: 0 when both are 0, infinite when only one is.
double moved(double a, double b) {
  const double lo = std::min(a, b), hi = std::max(a, b);
  if (hi == 0) return 0.0;
  return lo == 0 ? INFINITY : hi / lo - 1;
}

}  // namespace

std::string to_string(TimingFigure f) {
  return std::string(to_string(f.statistic)) + (f.ratio ? " / calibration" : "");
}

double TimedCell::value(TimingFigure f) const {
  return f.ratio ? ratio_of(full_ms, calibration_ms, f.statistic) : statistic(full_ms, f.statistic);
}

TimingRecord timing_record(const std::vector<SceneEvaluation>& scenes, const Provenance& p,
                           const Machine& machine) {
  TimingRecord r{p.commit, p.cpu, {}, machine};
  for (const SceneEvaluation& se : scenes)
    for (const EngineEvaluation& ev : se.engines)
      for (const StepEvaluation& st : ev.sweep)
        if (st.timing) r.cells.push_back(timed_cell(se.scene.name, ev.name, st));
  return r;
}

std::string timing_json(const TimingRecord& record) {
  const Machine& m = record.machine;
  const Json machine{{"cpu", m.cpu},       {"cpu_id", m.cpu_id},
                     {"caches", m.caches}, {"logical_cpus", m.logical_cpus},
                     {"kernel", m.kernel}, {"installation", m.installation}};
  std::string out = "{\n  \"commit\": " + json_text(Json(record.commit)) +
                    ",\n  \"cpu\": " + json_text(Json(record.cpu)) +
                    ",\n  \"machine\": " + json_text(machine) + ",\n  \"cells\": [";
  for (std::size_t i = 0; i < record.cells.size(); ++i)
    out += (i ? ",\n    " : "\n    ") + json_text(cell_json(record.cells[i]));
  return out + (record.cells.empty() ? "]\n}\n" : "\n  ]\n}\n");
}

TimingRecord parse_timing_record(const std::string& text, const std::string& file) {
  const JsonReader r{file};
  Json root;
  try {
    root = parse_json<Json>(text);
  } catch (const std::exception& e) {  // a syntax error, a number beyond double's range, depth
    r.fail("", "not a timings record: " + excerpt(e.what(), 120));
  }
  if (!root.is_object()) r.fail("", "not a timings record: expected a JSON object");
  TimingRecord record{r.text(root, "commit", ""), r.text(root, "cpu", ""), {}, {}};
  if (root.contains("machine")) record.machine = r.machine(r.at(root, "machine", ""));
  const Json& cells = r.at(root, "cells", "");
  if (!cells.is_array())
    r.fail("cells", std::string("expected an array, got ") + cells.type_name());
  for (std::size_t i = 0; i < cells.size(); ++i)
    record.cells.push_back(r.cell(cells[i], "cells[" + std::to_string(i) + "]"));
  return record;
}

TimingRecord read_timing_record(const std::string& file, Links links) {
  return parse_timing_record(
      read_regular_file(file, std::int64_t{16} << 20, "16 MiB, for a timings record", links), file);
}

PreviousTimings read_previous_timings(const std::string& folder) {
  const std::filesystem::path file = std::filesystem::path(folder) / kTimingsFile;
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::symlink_status(file, ec);
  if (!std::filesystem::exists(status))
    return {std::nullopt,
            "No earlier timings in this folder (" + file.generic_string() +
                "): write the report into the same folder again for the two-run figure.",
            ""};
  try {
    // Never through a link: the file a link names is not one dropcheck wrote, and a parse error
    // would quote its bytes into the report.
    if (std::filesystem::is_symlink(status))
      throw InputError(file.generic_string(), 0, "",
                       "is a symbolic link, not the file a report wrote");
    return {read_timing_record(file.generic_string(), Links::refuse), "", ""};  // O_NOFOLLOW too
  } catch (const InputError& e) {
    return {std::nullopt,
            std::string("The timings of the report this one replaced could not be read (") +
                e.what() + "): no comparison.",
            e.what()};
  }
}

namespace {

// True when two cells timed the same work the same way: the same copies, repeats and number of
// samples (a --timing-smoke record, another scene under the same name or another engine's nominal
// cost is not comparable).
bool comparable(const TimedCell& a, const TimedCell& b) {
  return a.replicas == b.replicas && a.repeats == b.repeats && a.full_ms.size() == b.full_ms.size();
}

// Every cell found once in each record, comparable and finite, with its figure before and now
// (moved left at 0).
std::vector<MovedCell> pairs(const TimingRecord& before, const TimingRecord& now, TimingFigure f) {
  const std::map<Key, const TimedCell*> old = by_key(before);
  std::vector<MovedCell> all;
  for (const auto& [key, cell] : by_key(now)) {
    const auto it = old.find(key);
    if (!cell || it == old.end() || !it->second || !comparable(*cell, *it->second)) continue;
    const double a = it->second->value(f), b = cell->value(f);
    if (std::isfinite(a) && std::isfinite(b) && a > 0.0 && b > 0.0)
      all.push_back({cell->scene, cell->engine, cell->h, a, b, 0.0});
  }
  return all;
}

}  // namespace

double slowdown_threshold(const std::string& engine) {
  // Each engine's threshold is declared with it (adapters/engines.txt, where it was measured); an
  // engine not measured (an external one) gets the largest of them.
  const EngineListing* listing = find_engine_listing(engine);
  if (listing && listing->slowdown_threshold > 0) return listing->slowdown_threshold;
  double largest = 0.0;
  for (const EngineListing& l : engine_listings())
    largest = std::max(largest, l.slowdown_threshold);
  return largest;
}

std::vector<Slowdown> slowdowns(const TimingRecord& before, const TimingRecord& now,
                                std::size_t* judged) {
  std::vector<Slowdown> out;
  if (judged) *judged = 0;
  if (!machine_differences(before.machine, now.machine).empty()) return out;
  std::vector<MovedCell> cells = pairs(before, now, kAlertFigure);
  if (judged) *judged = cells.size();
  std::map<std::string, std::vector<double>> by_engine;
  for (MovedCell& m : cells) {
    m.moved = m.now / m.before - 1.0;
    by_engine[m.engine].push_back(m.moved);
  }
  std::map<std::string, double> median;
  for (const auto& [engine, moves] : by_engine) median[engine] = quantile(moves, 0.5);
  for (const MovedCell& m : cells) {
    const double threshold = slowdown_threshold(m.engine);
    if (median[m.engine] > threshold && m.moved > threshold)
      out.push_back({m, threshold, median[m.engine]});
  }
  std::stable_sort(out.begin(), out.end(), [](const Slowdown& a, const Slowdown& b) {
    return a.cell.moved > b.cell.moved;
  });
  return out;
}

TimingComparison compare_timings(const TimingRecord& before, const TimingRecord& now,
                                 TimingFigure figure, double tolerance, std::size_t keep) {
  TimingComparison out;
  out.figure = figure;
  out.tolerance = tolerance;
  std::vector<MovedCell> all = pairs(before, now, figure);
  for (MovedCell& m : all) m.moved = moved(m.before, m.now);
  out.cells = all.size();
  out.agree = std::count_if(all.begin(), all.end(),
                            [&](const MovedCell& m) { return m.moved <= tolerance; });
  // Largest move first; equal moves in key order (the map's), so that the list is deterministic.
  std::stable_sort(all.begin(), all.end(),
                   [](const MovedCell& a, const MovedCell& b) { return a.moved > b.moved; });
  if (!all.empty()) {
    std::vector<double> m;
    for (const MovedCell& c : all) m.push_back(c.moved);
    out.median_moved = quantile(std::move(m), 0.5);
  }
  all.resize(std::min(keep, all.size()));
  out.worst = std::move(all);
  return out;
}

}  // namespace dropcheck
