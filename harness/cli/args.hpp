// Command-line arguments, parsed with CLI11 from a declared spec: positionals plus --name VALUE
// options (repeatable) and --flags; every command answers --help.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace dropcheck {

// One --option: a value option when `value_name` is set ("FILE"), else a flag.
struct OptionSpec {
  std::string name;         // "--engine"
  std::string value_name;   // "E"; empty for a flag
  std::string help;         // one line for --help
  bool repeatable = false;  // --engine A --engine B keeps both; otherwise given at most once
};

// A command's arguments: its positionals and options, for parsing and for --help.
struct CommandSpec {
  std::string name;             // "run"
  std::string summary;          // one paragraph for --help
  std::string positional_name;  // "FILE"; empty when the command takes none
  std::string positional_help;  // one line for --help
  int min_positional = 0;       // how many positionals are required
  int max_positional = 0;       // -1 for any number
  std::vector<OptionSpec> options;
};

// What `--help` asked for: the usage text, printed to stdout with exit 0.
struct HelpRequested {
  std::string text;
};

struct Args {
  std::vector<std::string> positional;
  std::map<std::string, std::vector<std::string>> options;  // "--engine" -> {"ours", "ode"}
  std::set<std::string> flags;                              // "--check"

  // The last value of `name`, or `fallback` when absent.
  std::string value(const std::string& name, const std::string& fallback = "") const;
  const std::vector<std::string>& values(const std::string& name) const;
  bool has(const std::string& name) const { return options.count(name) || flags.count(name); }
};

// Parses argv (without the command's name) by `spec`. Throws HelpRequested for -h/--help, and
// InputError naming the option for an unknown option, a missing or empty value, a non-repeatable
// option given twice, or too few / too many positionals.
Args parse_args(const CommandSpec& spec, const std::vector<std::string>& argv);

// The --help text of `spec`.
std::string help_text(const CommandSpec& spec);

}  // namespace dropcheck
