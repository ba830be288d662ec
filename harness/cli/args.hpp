// Command-line arguments: positionals plus --name VALUE options (repeatable) and --flags.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace dropcheck {

struct Args {
  std::vector<std::string> positional;
  std::map<std::string, std::vector<std::string>> options;  // "--engine" -> {"ours", "ode"}
  std::set<std::string> flags;                              // "--help"

  // The last value of `name`, or `fallback` when absent.
  std::string value(const std::string& name, const std::string& fallback = "") const;
  const std::vector<std::string>& values(const std::string& name) const;
  bool has(const std::string& name) const { return options.count(name) || flags.count(name); }
};

// Splits argv; `with_value` names the options that take a value, `flag_names` those that do not.
// Throws InputError (usage) for an unknown option or a missing value.
Args parse_args(const std::vector<std::string>& argv, const std::set<std::string>& with_value,
                const std::set<std::string>& flag_names);

}  // namespace dropcheck
