#include "harness/measure/timing_record.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <tuple>

#include "harness/core/input_error.hpp"
#include "harness/io/bounded_read.hpp"

namespace dropcheck {
namespace {

using Json = nlohmann::ordered_json;

TimedCell timed_cell(const std::string& scene, const std::string& engine,
                     const StepEvaluation& st) {
  const Timing& t = *st.timing;
  return {scene,
          engine,
          st.h.text,
          1e3 * t.median_per_sim_s,
          1e3 * t.q1_per_sim_s,
          1e3 * t.q3_per_sim_s,
          1e3 * t.min_per_sim_s,
          1e3 * t.bare_median_per_sim_s,
          t.samples,
          t.replicas,
          t.repeats};
}

Json cell_json(const TimedCell& c) {
  return {{"scene", c.scene},
          {"engine", c.engine},
          {"h", c.h},
          {"median_ms", c.median_ms},
          {"q1_ms", c.q1_ms},
          {"q3_ms", c.q3_ms},
          {"min_ms", c.min_ms},
          {"bare_median_ms", c.bare_median_ms},
          {"samples", c.samples},
          {"replicas", c.replicas},
          {"repeats", c.repeats}};
}

// Reads the typed values of a parsed record, naming the key of the first that is wrong.
struct Reader {
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
    return v.get<std::string>();
  }
  double number(const Json& object, const std::string& key, const std::string& where) const {
    const Json& v = at(object, key, where);
    if (!v.is_number()) fail(where + key, std::string("expected a number, got ") + v.type_name());
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < 0) fail(where + key, "expected a finite number >= 0");
    return x;
  }
  int count(const Json& object, const std::string& key, const std::string& where) const {
    const Json& v = at(object, key, where);
    if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() > 1 << 30)
      fail(where + key, "expected a whole number from 0 to 2^30");
    return v.get<int>();
  }
  TimedCell cell(const Json& c, const std::string& name) const {
    if (!c.is_object()) fail(name, std::string("expected an object, got ") + c.type_name());
    const std::string where = name + ".";
    return {text(c, "scene", where),    text(c, "engine", where),
            text(c, "h", where),        number(c, "median_ms", where),
            number(c, "q1_ms", where),  number(c, "q3_ms", where),
            number(c, "min_ms", where), number(c, "bare_median_ms", where),
            count(c, "samples", where), count(c, "replicas", where),
            count(c, "repeats", where)};
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

// max/min - 1 of two medians: 0 when both are 0, infinite when only one is.
double moved(double a, double b) {
  const double lo = std::min(a, b), hi = std::max(a, b);
  if (hi == 0) return 0.0;
  return lo == 0 ? INFINITY : hi / lo - 1;
}

}  // namespace

TimingRecord timing_record(const std::vector<SceneEvaluation>& scenes, const Provenance& p) {
  TimingRecord r{p.commit, p.cpu, {}};
  for (const SceneEvaluation& se : scenes)
    for (const EngineEvaluation& ev : se.engines)
      for (const StepEvaluation& st : ev.sweep)
        if (st.timing) r.cells.push_back(timed_cell(se.scene.name, ev.name, st));
  return r;
}

std::string timing_json(const TimingRecord& record) {
  std::string out = "{\n  \"commit\": " + Json(record.commit).dump() +
                    ",\n  \"cpu\": " + Json(record.cpu).dump() + ",\n  \"cells\": [";
  for (std::size_t i = 0; i < record.cells.size(); ++i)
    out += (i ? ",\n    " : "\n    ") + cell_json(record.cells[i]).dump();
  return out + (record.cells.empty() ? "]\n}\n" : "\n  ]\n}\n");
}

TimingRecord parse_timing_record(const std::string& text, const std::string& file) {
  const Reader r{file};
  Json root;
  try {
    root = Json::parse(text);
  } catch (const Json::exception& e) {  // a syntax error, or a number beyond double's range
    r.fail("", std::string("not a timings record: ") + e.what());
  }
  if (!root.is_object()) r.fail("", "not a timings record: expected a JSON object");
  TimingRecord record{r.text(root, "commit", ""), r.text(root, "cpu", ""), {}};
  const Json& cells = r.at(root, "cells", "");
  if (!cells.is_array())
    r.fail("cells", std::string("expected an array, got ") + cells.type_name());
  for (std::size_t i = 0; i < cells.size(); ++i)
    record.cells.push_back(r.cell(cells[i], "cells[" + std::to_string(i) + "]"));
  return record;
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
    return {parse_timing_record(read_regular_file(file.string(), std::int64_t{16} << 20,
                                                  "16 MiB, for a timings record"),
                                file.generic_string()),
            "", ""};
  } catch (const InputError& e) {
    return {std::nullopt,
            std::string("The timings of the report this one replaced could not be read (") +
                e.what() + "): no comparison.",
            e.what()};
  }
}

TimingComparison compare_timings(const TimingRecord& before, const TimingRecord& now,
                                 double tolerance, std::size_t keep) {
  TimingComparison out;
  out.tolerance = tolerance;
  const std::map<Key, const TimedCell*> old = by_key(before);
  std::vector<MovedCell> all;
  for (const auto& [key, cell] : by_key(now)) {
    const auto it = old.find(key);
    if (!cell || it == old.end() || !it->second) continue;
    all.push_back({*it->second, *cell, moved(it->second->median_ms, cell->median_ms)});
  }
  out.cells = all.size();
  out.agree = std::count_if(all.begin(), all.end(),
                            [&](const MovedCell& m) { return m.moved <= tolerance; });
  // Largest move first; equal moves in key order (the map's), so that the list is deterministic.
  std::stable_sort(all.begin(), all.end(),
                   [](const MovedCell& a, const MovedCell& b) { return a.moved > b.moved; });
  if (!all.empty()) {
    std::vector<double> m;
    for (const MovedCell& c : all) m.push_back(c.moved);
    std::nth_element(m.begin(), m.begin() + m.size() / 2, m.end());
    out.median_moved = m[m.size() / 2];
  }
  all.resize(std::min(keep, all.size()));
  out.worst = std::move(all);
  return out;
}

}  // namespace dropcheck
