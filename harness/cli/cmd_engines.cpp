// dropcheck engines: name, version, scalar, capabilities, discrete law, damping mapping.
#include <algorithm>
#include <array>
#include <memory>

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
  // Each column as wide as its widest cell, so that a long name or mapping shifts nothing after it;
  // an engine not compiled in is one line saying why, in its place.
  struct Row {
    std::array<std::string, 6> cells;
    std::string unavailable;
  };
  std::vector<Row> rows{
      {{"engine", "version", "scalar", "capabilities", "discrete law", "damping mapping"}, ""}};
  for (const std::string& name : known_engine_names()) {
    std::unique_ptr<Engine> e = make_engine(name);
    if (!e) {
      rows.push_back({{}, name + "  (" + engine_unavailable_reason(name) + ")"});
      continue;
    }
    const EngineInfo i = e->info();
    rows.push_back({{i.name, i.version, to_string(i.scalar), to_string(i.capabilities),
                     to_string(i.law), i.damping_mapping},
                    ""});
  }
  std::array<int, 6> width{};
  for (const Row& row : rows)
    for (std::size_t c = 0; c < row.cells.size(); ++c)
      width[c] = std::max(width[c], static_cast<int>(row.cells[c].size()));
  for (const Row& row : rows) {
    const auto& c = row.cells;
    out << (row.unavailable.empty()
                ? printf_string("%-*s %-*s %-*s %-*s %-*s %s", width[0], c[0], width[1], c[1],
                                width[2], c[2], width[3], c[3], width[4], c[4], c[5])
                : row.unavailable)
        << "\n";
  }
  return kExitOk;
}

}  // namespace dropcheck
