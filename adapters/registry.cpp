// The registry: the table adapters/CMakeLists.txt generates from adapters/engines.txt, one row per
// engine known. An engine whose library was not found at configure time is listed with the reason,
// never silently missing.
#include "harness/core/registry.hpp"

#include <stdexcept>

#include "adapters.hpp"
#include "exec.hpp"
#include "harness/core/engine_listing.hpp"

namespace dropcheck {

struct EngineEntry {
  const char* name;
  std::unique_ptr<Engine> (*make)();  // nullptr: not compiled in
  double (*bare)(const Scene&, double);
};

// The adapters' factories and bare loops (declared at namespace scope, where they are defined), and
// kEngineTable (const, so internal to this file).
#include "engine_table.inc"

namespace {

const EngineEntry* find(const std::string& name) {
  for (const EngineEntry& e : kEngineTable)
    if (name == e.name) return &e;
  return nullptr;
}

// "ours, ours-f64, ..., exec:PATH, FILE.toml": what an --engine may name.
std::string known_names_text() {
  std::string text;
  for (const EngineEntry& e : kEngineTable) text += std::string(e.name) + ", ";
  return text + "exec:PATH, FILE.toml";
}

}  // namespace

const std::vector<std::string>& known_engine_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const EngineEntry& e : kEngineTable) n.push_back(e.name);
    return n;
  }();
  return names;
}

std::vector<std::string> available_engine_names() {
  std::vector<std::string> names;
  for (const EngineEntry& e : kEngineTable)
    if (e.make) names.push_back(e.name);
  return names;
}

std::unique_ptr<Engine> make_engine(const std::string& name) {
  if (is_exec_spec(name)) return make_exec_engine(parse_exec_spec(name));
  const EngineEntry* e = find(name);
  return e && e->make ? e->make() : nullptr;
}

std::string engine_unavailable_reason(const std::string& name) {
  if (is_exec_spec(name)) {
    parse_exec_spec(name);  // throws InputError for a bad engine file or path
    return {};
  }
  const EngineEntry* e = find(name);
  if (!e) return "unknown engine (known: " + known_names_text() + ": docs/protocol.md)";
  if (!e->make)
    return "not compiled in (library not found; CMake option " + find_engine_listing(name)->option +
           ")";
  return {};
}

double bare_step_loop(const std::string& engine, const Scene& scene, double h) {
  const EngineEntry* e = find(engine);
  if (!e || !e->bare)
    throw std::invalid_argument("bare_step_loop: engine '" + engine + "' is not compiled in");
  return e->bare(scene, h);
}

}  // namespace dropcheck
