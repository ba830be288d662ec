// dropcheck engines: name, version, scalar, capabilities, discrete law, damping mapping.
#include "args.hpp"
#include "cli.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/registry.hpp"

namespace dropcheck {

const CommandSpec& engines_spec() {
  static const CommandSpec spec{
      "engines",
      "Lists every engine dropcheck knows: version, scalar, capabilities, discrete law and "
      "damping mapping, or why it is not compiled in.",
      "",
      "",
      0,
      0,
      {}};
  return spec;
}

int cmd_engines(const std::vector<std::string>& argv, std::ostream& out, std::ostream&) {
  parse_args(engines_spec(), argv);
  const char* row = "%-11s %-14s %-6s %-53s %-38s %s\n";
  out << printf_string(row, "engine", "version", "scalar", "capabilities", "discrete law",
                       "damping mapping");
  for (const std::string& name : known_engine_names()) {
    std::unique_ptr<Engine> e = make_engine(name);
    if (!e) {
      out << name << "  (" << engine_unavailable_reason(name) << ")\n";
      continue;
    }
    const EngineInfo i = e->info();
    out << printf_string(row, i.name.c_str(), i.version.c_str(), to_string(i.scalar),
                         to_string(i.capabilities).c_str(), to_string(i.law).c_str(),
                         i.damping_mapping.c_str());
  }
  return kExitOk;
}

}  // namespace dropcheck
