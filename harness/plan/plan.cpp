#include "harness/plan/plan.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <set>

#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/core/trajectory_hash.hpp"
#include "harness/io/bounded_read.hpp"
#include "harness/io/json_text.hpp"
#include "harness/plan/axes.hpp"
#include "harness/run/run_limits.hpp"
#include "harness/scene/scene_loader.hpp"

namespace dropcheck {
namespace {

using Json = nlohmann::ordered_json;

constexpr const char* kPlanFormat = "dropcheck-plan/1";

// Checks that each value of each axis applies to each scene on its own, and that each engine's run
// there is within the limits a run is held to (run_limits.hpp: steps, recorded samples' memory,
// float range), so that `run --dt` and a plan refuse the same steps. The product is not built: a
// combination that cannot apply becomes its cell's record.
void validate_axes(const SweepSpec& sweep, const Plan& plan, std::span<const EngineInfo> engines) {
  for (std::size_t i = 0; i < sweep.axes.size(); ++i) {
    const Axis& a = sweep.axes[i];
    for (const PlanScene& s : plan.scenes)
      for (const std::string& v : a.values) {
        const auto refuse = [&](const std::string& why) {
          return InputError(sweep.file, a.line, "axis[" + std::to_string(i) + "]",
                            a.name + " = " + v + " on scene " + s.name + ": " + why);
        };
        CellSetup c;
        try {
          c = setup_cell(s.text, s.file, sweep.engines.front(), {&a, 1}, {&v, 1});
        } catch (const InputError& e) {
          throw refuse(e.what());
        }
        for (const EngineInfo& info : engines)
          if (const std::string why = run_refusal(info, c.scene, c.h.seconds, RunOptions{});
              !why.empty())
            throw refuse(info.name + ": " + why);
      }
  }
}

// The plan as JSON. With `paths` false, without the sweep file's and the scenes' paths: what the
// hash covers, so that the same sweep planned from another folder is the same plan.
Json content(const Plan& p, bool paths = true) {
  Json j;
  j["format"] = kPlanFormat;
  if (paths) j["sweep"] = p.sweep;
  j["description"] = p.description;
  j["engines"] = p.engines;
  if (paths && !p.external.empty()) {
    Json external = Json::array();
    for (const ExternalEngine& e : p.external)
      external.push_back({{"engine", e.id}, {"file", e.file}});
    j["external"] = external;
  }
  Json measures = Json::array();
  for (Measure m : p.measures) measures.push_back(to_string(m));
  j["measure"] = measures;
  Json axes = Json::array();
  for (const Axis& a : p.axes)
    axes.push_back(
        {{a.kind == AxisKind::scene_key ? "key" : "name", a.name}, {"values", a.values}});
  j["axes"] = axes;
  Json scenes = Json::array();
  for (const PlanScene& s : p.scenes) {
    Json scene{{"name", s.name}};
    if (paths) scene["file"] = s.file;
    scene["text"] = s.text;
    scenes.push_back(scene);
  }
  j["scenes"] = scenes;
  return j;
}

std::string hash_of(const Plan& p) {
  return fnv1a_hex(json_text(content(p, false)));
}

// What a plan read back must hold, however its hash was made: each scene a valid scene of its name,
// names unique and printable, each axis value canonical and unique (so that a key names one cell
// and one cell has one key).
void validate(const Plan& p) {
  std::set<std::string> names;
  for (const PlanScene& s : p.scenes) {
    if (find_unsafe_in_line(s.file) != std::string::npos)
      throw std::invalid_argument("a control character in scene file " + excerpt(s.file));
    const Scene scene = parse_scene(s.text, s.file);  // InputError: passed on
    if (scene.name != s.name)
      throw std::invalid_argument("scene " + excerpt(s.name) + " is named " + excerpt(scene.name) +
                                  " by its text");
    if (!names.insert(s.name).second)
      throw std::invalid_argument("two scenes named " + excerpt(s.name));
  }
  const std::set<std::string> engines(p.engines.begin(), p.engines.end());
  if (engines.size() != p.engines.size()) throw std::invalid_argument("an engine listed twice");
  std::set<std::string> axes;
  for (const Axis& a : p.axes) {
    if (a.name.empty() || find_unsafe_in_line(a.name) != std::string::npos ||
        a.name.find_first_of("|=") != std::string::npos || !axes.insert(a.name).second)
      throw std::invalid_argument("axis name " + excerpt(a.name));
    std::set<std::string> values;
    for (const std::string& v : a.values) {
      check_canonical_value(a, v);  // InputError: passed on
      if (!values.insert(v).second) throw std::invalid_argument("value " + v + " twice");
    }
  }
}

Plan from_json(const Json& j) {
  if (j.at("format").get<std::string>() != kPlanFormat)
    throw std::invalid_argument("format is not " + std::string(kPlanFormat));
  Plan p;
  p.sweep = j.at("sweep").get<std::string>();
  p.description = j.at("description").get<std::string>();
  p.engines = j.at("engines").get<std::vector<std::string>>();
  // A registry name (lower-case letters, digits, '-'), or an external engine's id NAME@FP: a plan
  // is data and names no program to start (`sweep --engine-file` does). A name this build lacks is
  // a skipped cell.
  for (const std::string& e : p.engines) {
    if (is_external_engine_id(e)) {
      p.external.push_back({e, "", ""});
      continue;
    }
    if (e.empty() || e.size() > 32 ||
        e.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-") != std::string::npos)
      throw std::invalid_argument("unknown engine " + excerpt(e));
  }
  if (j.contains("external"))
    for (const Json& x : j.at("external")) {
      const std::string id = x.at("engine").get<std::string>(),
                        file = x.at("file").get<std::string>();
      const auto e = std::find_if(p.external.begin(), p.external.end(),
                                  [&](const ExternalEngine& k) { return k.id == id; });
      if (e == p.external.end() || !e->file.empty())
        throw std::invalid_argument("external engine " + excerpt(id) +
                                    " is not one of the engines");
      if (find_unsafe_in_line(file) != std::string::npos || file.size() > 4096)
        throw std::invalid_argument("external engine " + excerpt(id) + "'s file " + excerpt(file));
      e->file = file;
    }
  for (const Json& m : j.at("measure")) {
    const std::optional<Measure> measure = measure_named(m.get<std::string>());
    if (!measure) throw std::invalid_argument("unknown measure " + excerpt(m.get<std::string>()));
    p.measures.push_back(*measure);
  }
  for (const Json& a : j.at("axes")) {
    Axis axis;
    if (a.contains("key")) {
      axis.kind = AxisKind::scene_key;
      axis.name = a.at("key").get<std::string>();
    } else {
      axis.name = a.at("name").get<std::string>();
      const std::optional<AxisKind> kind = named_axis(axis.name);
      if (!kind) throw std::invalid_argument("unknown axis " + excerpt(axis.name));
      axis.kind = *kind;
    }
    axis.values = a.at("values").get<std::vector<std::string>>();
    if (axis.values.empty())
      throw std::invalid_argument("axis " + excerpt(axis.name) + " has no values");
    p.axes.push_back(std::move(axis));
  }
  for (const Json& s : j.at("scenes"))
    p.scenes.push_back({s.at("name").get<std::string>(), s.at("file").get<std::string>(),
                        s.at("text").get<std::string>()});
  if (p.scenes.empty() || p.engines.empty())
    throw std::invalid_argument("a plan needs scenes and engines");
  double cells = static_cast<double>(p.scenes.size()) * static_cast<double>(p.engines.size());
  for (const Axis& a : p.axes) cells *= static_cast<double>(a.values.size());
  if (cells > static_cast<double>(kMaxCells))
    throw std::invalid_argument("more than " + std::to_string(kMaxCells) + " cells");
  p.hash = j.at("hash").get<std::string>();
  validate(p);
  return p;
}

}  // namespace

std::size_t Plan::cell_count() const {
  std::size_t n = scenes.size() * engines.size();
  for (const Axis& a : axes) n *= a.values.size();
  return n;
}

Cell Plan::cell(std::size_t i) const {
  Cell c;
  c.values.resize(axes.size());
  for (std::size_t k = axes.size(); k-- > 0;) {
    c.values[k] = i % axes[k].values.size();
    i /= axes[k].values.size();
  }
  c.engine = i % engines.size();
  c.scene = i / engines.size();
  c.key = scenes[c.scene].name + "|" + engines[c.engine];
  for (std::size_t k = 0; k < axes.size(); ++k)
    c.key += "|" + axes[k].name + "=" + axes[k].values[c.values[k]];
  return c;
}

std::string Plan::runs(std::size_t engine) const {
  for (const ExternalEngine& e : external)
    if (e.id == engines[engine]) return e.runs;
  return engines[engine];
}

bool Plan::has(Measure m) const {
  return std::find(measures.begin(), measures.end(), m) != measures.end();
}

Plan make_plan(const SweepSpec& sweep, std::span<const EngineInfo> engines) {
  Plan p;
  p.sweep = sweep.file;
  p.description = sweep.description;
  p.engines = sweep.engines;
  p.external = sweep.external;
  p.axes = sweep.axes;
  p.measures = sweep.measures;
  std::set<std::string> names;
  for (const std::string& file : sweep.scene_files) {
    std::string text = read_scene_text(file);
    const Scene s = parse_scene(text, file);
    if (!names.insert(s.name).second)
      throw InputError(sweep.file, 0, "scenes",
                       "two scenes are named " + excerpt(s.name) + " (the second: " + file + ")");
    p.scenes.push_back({s.name, file, std::move(text)});
  }
  validate_axes(sweep, p, engines);
  p.hash = hash_of(p);
  return p;
}

std::string plan_text(const Plan& plan) {
  Json j = content(plan);
  j["hash"] = plan.hash;
  return json_text(j, 1) + "\n";
}

Plan read_plan(const std::string& path) {
  return parse_plan(read_regular_file(path, kMaxPlanBytes, "256 MiB, for a plan"), path);
}

Plan parse_plan(const std::string& text, const std::string& path, bool check_hash) {
  Plan p;
  try {
    p = from_json(parse_json<Json>(text));
  } catch (const InputError& e) {
    throw InputError(path, 0, "", std::string("not a valid plan: ") + e.what());
  } catch (const std::exception& e) {
    // The JSON parser's message quotes the text it stopped at as it is: escaped and cut here.
    throw InputError(path, 0, "", std::string("not a dropcheck plan: ") + excerpt(e.what(), 200));
  }
  if (check_hash && hash_of(p) != p.hash)
    throw InputError(path, 0, "hash",
                     "the plan's content does not match its hash " + excerpt(p.hash) +
                         " (edited after `dropcheck plan`? plan the sweep again)");
  return p;
}

std::string plan_hash(const Plan& plan) {
  return hash_of(plan);
}

std::size_t shard_of(std::string_view key, std::size_t n) {
  return static_cast<std::size_t>(fnv1a(key) % n);
}

}  // namespace dropcheck
