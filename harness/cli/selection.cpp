#include "selection.hpp"

#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/core/timestep.hpp"

namespace dropcheck {
void refuse_name_clashes(const std::vector<std::pair<std::string, std::string>>& engines) {
  for (std::size_t i = 0; i < engines.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (engines[i].second == engines[j].second)
        throw InputError("", 0, "--engine " + excerpt(engines[i].first),
                         "announces the name '" + escape_controls(engines[i].second) +
                             "', as --engine " + excerpt(engines[j].first) +
                             " does; two engines cannot share a name (set `name` in an engine "
                             "file)");
}

std::vector<SelectedEngine> select_engines(const std::vector<std::string>& requested,
                                           const Scene& scene) {
  const std::vector<std::string> names = requested.empty() ? available_engine_names() : requested;
  std::vector<SelectedEngine> out;
  for (const std::string& name : names) {
    SelectedEngine s{name, make_engine(name), {}};
    if (!s.engine) {
      const std::string why = engine_unavailable_reason(name);
      if (why.rfind("unknown", 0) == 0)
        throw InputError("", 0, "--engine " + escape_controls(name), why);
      s.skipped_because = why;
    } else if (std::string why = s.engine->cannot_run(scene); !why.empty()) {
      s.name = s.engine->info().name;  // an engine file's own name, not its path
      s.engine.reset();
      s.skipped_because = why;
    }
    out.push_back(std::move(s));
  }
  std::vector<std::pair<std::string, std::string>> announced;
  for (const SelectedEngine& e : out)
    if (e.engine) announced.emplace_back(e.name, e.engine->info().name);
  refuse_name_clashes(announced);
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
