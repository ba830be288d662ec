// The one table of engines. An engine whose library was not found at configure time is listed
// with the reason, never silently missing.
#include "harness/core/registry.hpp"

#include <algorithm>

#include "adapters.hpp"
#include "exec.hpp"

namespace dropcheck {
namespace {

using Factory = std::unique_ptr<Engine> (*)();

struct Entry {
  const char* name;
  Factory make;  // nullptr: not compiled in
  const char* option;
};

#ifndef DROPCHECK_HAVE_BULLET
std::unique_ptr<Engine> (*const make_bullet_ptr)() = nullptr;
#else
std::unique_ptr<Engine> (*const make_bullet_ptr)() = make_bullet;
#endif
#ifndef DROPCHECK_HAVE_ODE
std::unique_ptr<Engine> (*const make_ode_ptr)() = nullptr;
#else
std::unique_ptr<Engine> (*const make_ode_ptr)() = make_ode;
#endif
#ifndef DROPCHECK_HAVE_BOX2D
std::unique_ptr<Engine> (*const make_box2d_ptr)() = nullptr;
#else
std::unique_ptr<Engine> (*const make_box2d_ptr)() = make_box2d;
#endif
#ifndef DROPCHECK_HAVE_MUJOCO
std::unique_ptr<Engine> (*const make_mujoco_ptr)() = nullptr;
#else
std::unique_ptr<Engine> (*const make_mujoco_ptr)() = make_mujoco;
#endif
#ifndef DROPCHECK_HAVE_CHIPMUNK
std::unique_ptr<Engine> (*const make_chipmunk_ptr)() = nullptr;
#else
std::unique_ptr<Engine> (*const make_chipmunk_ptr)() = make_chipmunk;
#endif
#ifndef DROPCHECK_HAVE_SIMBODY
std::unique_ptr<Engine> (*const make_simbody_ptr)() = nullptr;
std::unique_ptr<Engine> (*const make_simbody_rkm_ptr)() = nullptr;
#else
std::unique_ptr<Engine> (*const make_simbody_ptr)() = make_simbody;
std::unique_ptr<Engine> (*const make_simbody_rkm_ptr)() = make_simbody_rkm;
#endif
#ifndef DROPCHECK_HAVE_DART
std::unique_ptr<Engine> (*const make_dart_ptr)() = nullptr;
#else
std::unique_ptr<Engine> (*const make_dart_ptr)() = make_dart;
#endif
#ifndef DROPCHECK_HAVE_WILDMAGIC
std::unique_ptr<Engine> (*const make_wildmagic_ptr)() = nullptr;
#else
std::unique_ptr<Engine> (*const make_wildmagic_ptr)() = make_wildmagic;
#endif

const Entry kEngines[] = {
    {"ours", make_ours_f32, ""},
    {"ours-f64", make_ours_f64, ""},
    {"bullet", make_bullet_ptr, "DROPCHECK_WITH_BULLET"},
    {"ode", make_ode_ptr, "DROPCHECK_WITH_ODE"},
    {"box2d", make_box2d_ptr, "DROPCHECK_WITH_BOX2D"},
    {"mujoco", make_mujoco_ptr, "DROPCHECK_WITH_MUJOCO"},
    {"chipmunk", make_chipmunk_ptr, "DROPCHECK_WITH_CHIPMUNK"},
    {"simbody", make_simbody_ptr, "DROPCHECK_WITH_SIMBODY"},
    {"simbody-rkm", make_simbody_rkm_ptr, "DROPCHECK_WITH_SIMBODY"},
    {"dart", make_dart_ptr, "DROPCHECK_WITH_DART"},
    {"wildmagic", make_wildmagic_ptr, "DROPCHECK_WITH_WILDMAGIC"},
};

const Entry* find(const std::string& name) {
  for (const Entry& e : kEngines)
    if (name == e.name) return &e;
  return nullptr;
}

}  // namespace

const std::vector<std::string>& known_engine_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const Entry& e : kEngines) n.push_back(e.name);
    return n;
  }();
  return names;
}

std::vector<std::string> available_engine_names() {
  std::vector<std::string> names;
  for (const Entry& e : kEngines)
    if (e.make) names.push_back(e.name);
  return names;
}

std::unique_ptr<Engine> make_engine(const std::string& name) {
  if (is_exec_spec(name)) return make_exec_engine(parse_exec_spec(name));
  const Entry* e = find(name);
  return e && e->make ? e->make() : nullptr;
}

std::string engine_unavailable_reason(const std::string& name) {
  if (is_exec_spec(name)) {
    parse_exec_spec(name);  // throws InputError for a bad engine file or path
    return {};
  }
  const Entry* e = find(name);
  if (!e)
    return "unknown engine (known: ours, ours-f64, bullet, ode, box2d, mujoco, chipmunk, simbody, "
           "simbody-rkm, dart, wildmagic, exec:PATH, FILE.toml: docs/protocol.md)";
  if (!e->make)
    return std::string("not compiled in (library not found; CMake option ") + e->option + ")";
  return {};
}

}  // namespace dropcheck
