// dropcheck engines: name, version, scalar, capabilities, discrete law, damping mapping.
#include <cstdio>

#include "args.hpp"
#include "cli.hpp"
#include "harness/core/registry.hpp"

namespace dropcheck {

int cmd_engines(const std::vector<std::string>& argv, std::ostream& out, std::ostream&) {
  parse_args(argv, {}, {});
  char line[512];
  std::snprintf(line, sizeof line, "%-9s %-14s %-6s %-22s %-36s %s\n", "engine", "version", "scalar",
                "capabilities", "discrete law", "damping mapping");
  out << line;
  for (const std::string& name : known_engine_names()) {
    std::unique_ptr<Engine> e = make_engine(name);
    if (!e) {
      out << name << "  (" << engine_unavailable_reason(name) << ")\n";
      continue;
    }
    const EngineInfo i = e->info();
    std::string caps = i.capabilities.contacts ? "free flight, contacts" : "free flight";
    if (i.capabilities.planar_only) caps += ", 2-D";
    std::snprintf(line, sizeof line, "%-9s %-14s %-6s %-22s %-36s %s\n", i.name.c_str(),
                  i.version.c_str(), to_string(i.scalar), caps.c_str(), to_string(i.law).c_str(),
                  i.damping_mapping.c_str());
    out << line;
  }
  return kExitOk;
}

}  // namespace dropcheck
