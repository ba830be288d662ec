#include "selection.hpp"

#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/scene/timestep.hpp"

namespace dropcheck {

std::vector<SelectedEngine> select_engines(const std::vector<std::string>& requested,
                                           const Scene& scene) {
  const std::vector<std::string> names = requested.empty() ? available_engine_names() : requested;
  std::vector<SelectedEngine> out;
  for (const std::string& name : names) {
    SelectedEngine s{name, make_engine(name), {}};
    if (!s.engine) {
      const std::string why = engine_unavailable_reason(name);
      if (why.rfind("unknown", 0) == 0) throw InputError("", 0, "--engine " + name, why);
      s.skipped_because = why;
    } else if (std::string why = s.engine->cannot_run(scene); !why.empty()) {
      s.engine.reset();
      s.skipped_because = why;
    }
    out.push_back(std::move(s));
  }
  return out;
}

Timestep step_from_flag(const std::string& flag_value, const Scene& scene) {
  if (flag_value.empty()) return scene.timestep;
  std::string why;
  std::optional<Timestep> t = parse_timestep(flag_value, why);
  if (!t) throw InputError("", 0, "--dt", why);
  if (std::string p = step_problem(scene.duration, t->seconds); !p.empty())
    throw InputError(scene.source, 0, "--dt " + flag_value, p);
  return *t;
}

}  // namespace dropcheck
