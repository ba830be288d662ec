#include "harness/plan/sweep_file.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/registry.hpp"
#include "harness/core/timestep.hpp"
#include "harness/io/bounded_read.hpp"
#include "harness/scene/toml_reader.hpp"

namespace dropcheck {
namespace {

namespace fs = std::filesystem;

// Largest sweep file: 1 MiB, like a scene.
constexpr long long kMaxSweepBytes = 1 << 20;
// Most values one range may give.
constexpr long long kMaxRangeCount = 1'000'000;

struct NamedAxis {
  const char* name;
  AxisKind kind;
};

constexpr NamedAxis kNamedAxes[] = {
    {"timestep", AxisKind::timestep},     {"damping_rate", AxisKind::damping_rate},
    {"gravity", AxisKind::gravity},       {"spring_stiffness", AxisKind::spring_stiffness},
    {"mass_ratio", AxisKind::mass_ratio}, {"initial_speed", AxisKind::initial_speed},
    {"scalar", AxisKind::scalar},
};

constexpr std::pair<const char*, Measure> kMeasures[] = {
    {"error", Measure::error}, {"own_law", Measure::own_law}, {"stability", Measure::stability},
    {"hash", Measure::hash},   {"timing", Measure::timing},
};

std::vector<std::string> string_list(const Reader& r, const std::string& key) {
  const toml::node* n = r.node(key);
  if (!n) r.fail(key, "required key is missing");
  const toml::array* a = n->as_array();
  if (!a || a->empty()) r.fail(key, "expected a non-empty array of strings", n);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    if (!e.is_string())
      r.fail(key + "[" + std::to_string(i) + "]",
             std::string("expected a string, got ") + Reader::type_name(e), &e);
    out.push_back(*e.value<std::string>());
  }
  return out;
}

// A scene entry: a .toml file, or a folder whose *.toml files (not recursive) are taken in name
// order. Relative to the sweep file's folder.
void add_scenes(const Reader& r, const std::string& entry, std::size_t i,
                std::vector<std::string>& out) {
  const std::string key = "scenes[" + std::to_string(i) + "]";
  fs::path p(entry);
  if (p.is_relative()) p = fs::path(r.file()).parent_path() / p;
  std::error_code ec;
  const fs::file_status st = fs::status(p, ec);
  if (fs::is_directory(st)) {
    std::vector<std::string> files;
    for (const fs::directory_entry& e : fs::directory_iterator(p, ec)) {
      if (e.path().extension() != ".toml") continue;
      // An entry of a folder is data from whoever filled it: a link could lead the read out of it.
      if (!fs::is_regular_file(e.symlink_status(ec)))
        r.fail(key, excerpt(e.path().string()) +
                        " is not a regular file (a link?): a scene "
                        "folder's entries are read only as its own files");
      files.push_back(e.path().lexically_normal().string());
    }
    if (files.empty()) r.fail(key, "folder " + excerpt(p.string()) + " holds no .toml scene");
    std::sort(files.begin(), files.end());
    out.insert(out.end(), files.begin(), files.end());
    return;
  }
  if (!fs::is_regular_file(st)) r.fail(key, "not a scene file or folder: " + excerpt(p.string()));
  out.push_back(p.lexically_normal().string());
}

// An engine file or exec:PATH, its path relative to the sweep file's folder: resolved, read and
// fingerprinted (never started).
ExternalEngine load_external(const Reader& r, const std::string& key, const std::string& e) {
  const bool exec = e.starts_with("exec:");
  fs::path p(exec ? e.substr(5) : e);
  if (p.is_relative()) p = fs::path(r.file()).parent_path() / p;
  const std::string file = (exec ? "exec:" : "") + p.lexically_normal().string();
  try {
    return {external_engine_id(file).value().id(), file, ""};
  } catch (const InputError& x) {
    r.fail(key, "engine " + excerpt(e) + ": " + x.what());
  }
}

void load_engines(const Reader& r, const std::vector<std::string>& known, SweepSpec& out) {
  const std::vector<std::string> engines = string_list(r, "engines");
  std::set<std::string> seen;
  for (std::size_t i = 0; i < engines.size(); ++i) {
    const std::string key = "engines[" + std::to_string(i) + "]";
    const std::string& e = engines[i];
    std::string id = e;
    if (is_external_engine_name(e)) {
      out.external.push_back(load_external(r, key, e));
      id = out.external.back().id;
    } else if (std::find(known.begin(), known.end(), e) == known.end()) {
      r.fail(key, "unknown engine " + excerpt(e) +
                      " (`dropcheck engines` lists the built-in ones; an external engine is an "
                      "engine file NAME.toml or exec:PATH)");
    }
    if (!seen.insert(id).second) r.fail(key, "engine " + excerpt(e) + " listed twice");
    out.engines.push_back(id);
  }
}

std::vector<Measure> load_measures(const Reader& r) {
  if (!r.has("measure"))
    return {Measure::error, Measure::own_law, Measure::stability, Measure::hash};
  std::vector<Measure> out;
  const std::vector<std::string> names = string_list(r, "measure");
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::optional<Measure> m = measure_named(names[i]);
    if (!m)
      r.fail("measure[" + std::to_string(i) + "]",
             "unknown measure " + excerpt(names[i]) +
                 " (known: error, own_law, stability, hash, timing)");
    if (std::find(out.begin(), out.end(), *m) != out.end())
      r.fail("measure[" + std::to_string(i) + "]", "measure " + names[i] + " listed twice");
    out.push_back(*m);
  }
  return out;
}

// A value's text in a cell key: a step as "1/60" or seconds, f32/f64, or the shortest number.
std::string value_text(const Reader& r, const Axis& axis, const std::string& key,
                       const toml::node& n) {
  if (axis.kind == AxisKind::timestep) return r.timestep(key, n).text;
  if (axis.kind == AxisKind::scalar) {
    const std::optional<std::string> s = n.value<std::string>();
    if (!n.is_string() || (*s != "f32" && *s != "f64"))
      r.fail(key, "expected \"f32\" or \"f64\"", &n);
    return *s;
  }
  return shortest(r.number(key, n));
}

std::vector<std::string> range_values(const Reader& r, const Axis& axis) {
  if (axis.kind == AxisKind::scalar) r.fail("from", "the scalar axis takes values, not a range");
  const double from = r.required_number("from"), to = r.required_number("to");
  const double count_d = r.required_number("count");
  if (count_d != std::floor(count_d) || count_d < 1 || count_d > kMaxRangeCount ||
      count_d > kMaxCells)
    r.fail("count", "must be a whole number from 1 to " + std::to_string(kMaxRangeCount));
  const auto count = static_cast<long long>(count_d);
  const std::string scale = r.string("scale", "linear");
  if (scale != "linear" && scale != "log") r.fail("scale", "expected \"linear\" or \"log\"");
  const bool log = scale == "log";
  if (log && !(from > 0.0 && to > 0.0)) r.fail("from", "a log range needs from > 0 and to > 0");
  std::vector<std::string> out;
  for (long long i = 0; i < count; ++i) {
    const double t = count == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(count - 1);
    const double v = log ? from * std::pow(to / from, t) : from + t * (to - from);
    const double exact = count > 1 && i == count - 1 ? to : v;  // the end lands where asked
    if (axis.kind == AxisKind::timestep) {
      std::string why;
      const std::optional<Timestep> h = parse_timestep(shortest(exact), why);
      if (!h) r.fail("from", "step " + shortest(exact) + ": " + why);
      out.push_back(h->text);
    } else {
      out.push_back(shortest(exact));
    }
  }
  return out;
}

Axis load_axis(const Reader& r) {
  r.only({"name", "key", "values", "from", "to", "count", "scale"});
  Axis a;
  a.line = static_cast<int>(r.table().source().begin.line);
  if (r.has("name") == r.has("key")) r.fail("name", "an axis has either name or key, not both");
  if (r.has("name")) {
    a.name = r.string("name", "");
    const std::optional<AxisKind> kind = named_axis(a.name);
    if (!kind)
      r.fail("name", "unknown axis " + excerpt(a.name) +
                         " (known: timestep, damping_rate, gravity, spring_stiffness, "
                         "mass_ratio, initial_speed, scalar; or key = \"a.scene.key\")");
    a.kind = *kind;
  } else {
    a.kind = AxisKind::scene_key;
    a.name = r.string("key", "");
    if (a.name.empty() || find_unsafe_in_line(a.name) != std::string::npos ||
        a.name.find_first_of("|= ") != std::string::npos)
      r.fail("key", "expected a scene key path such as \"world.linear_drag\"");
  }
  if (r.has("values") == r.has("from")) r.fail("values", "give either values or from/to/count");
  if (r.has("values")) {
    const toml::node* n = r.node("values");
    const toml::array* arr = n->as_array();
    if (!arr || arr->empty()) r.fail("values", "expected a non-empty array", n);
    for (std::size_t i = 0; i < arr->size(); ++i)
      a.values.push_back(value_text(r, a, "values[" + std::to_string(i) + "]", *arr->get(i)));
  } else {
    a.values = range_values(r, a);
  }
  // One value twice is one cell twice. A step is the same step however it is written ("0.0010"
  // and 0.001, "1/60" and 1/60's seconds are not: 1/60 has no exact decimal).
  std::map<std::string, std::string> seen;  // identity -> the text first seen
  for (const std::string& v : a.values) {
    std::string why;
    const std::optional<Timestep> h =
        a.kind == AxisKind::timestep ? parse_timestep(v, why) : std::nullopt;
    const std::string identity = h ? shortest(h->seconds) : v;
    if (const auto [it, added] = seen.emplace(identity, v); !added)
      r.fail("values",
             "value " + v + " appears twice" + (it->second == v ? "" : " (as " + it->second + ")"));
  }
  return a;
}

}  // namespace

SweepSpec load_sweep(const std::string& path, const std::vector<std::string>& known_engines) {
  const toml::table root =
      parse_toml(read_regular_file(path, kMaxSweepBytes, "1 MiB, for a sweep"), path);
  const Reader r(path, root, "");
  r.only({"description", "scenes", "engines", "measure", "axis"});
  SweepSpec s;
  s.file = path;
  s.description = r.string("description", "");
  const std::vector<std::string> entries = string_list(r, "scenes");
  for (std::size_t i = 0; i < entries.size(); ++i) add_scenes(r, entries[i], i, s.scene_files);
  load_engines(r, known_engines, s);
  s.measures = load_measures(r);
  // Counted as the axes load, so that a sweep asking for more cells stops before it allocates them.
  double cells = static_cast<double>(s.scene_files.size() * s.engines.size());
  if (const toml::array* axes = array_of_tables(r, "axis"))
    for (std::size_t i = 0; i < axes->size(); ++i) {
      const std::string key = "axis[" + std::to_string(i) + "]";
      Axis a = load_axis(Reader(path, *axes->get(i)->as_table(), key));
      for (const Axis& b : s.axes)
        if (b.name == a.name)
          throw InputError(path, a.line, key, "axis " + a.name + " given twice");
      cells *= static_cast<double>(a.values.size());
      if (cells > static_cast<double>(kMaxCells))
        throw InputError(path, a.line, key,
                         "the sweep reaches " + sig(cells, 3) + " cells here, more than the " +
                             sig(kMaxCells, 3) + " a plan may hold");
      s.axes.push_back(std::move(a));
    }
  return s;
}

const char* to_string(AxisKind kind) {
  for (const NamedAxis& n : kNamedAxes)
    if (n.kind == kind) return n.name;
  return "key";
}

const char* to_string(Measure m) {
  for (const auto& [name, measure] : kMeasures)
    if (measure == m) return name;
  return "?";
}

std::optional<AxisKind> named_axis(std::string_view name) {
  for (const NamedAxis& n : kNamedAxes)
    if (name == n.name) return n.kind;
  return std::nullopt;
}

std::optional<Measure> measure_named(std::string_view name) {
  for (const auto& [n, m] : kMeasures)
    if (name == n) return m;
  return std::nullopt;
}

}  // namespace dropcheck
