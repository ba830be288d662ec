// The dropcheck command line (contract in docs/design.md "CLI"). Exit codes: 0 success, 1 a check
// failed, 2 bad input or usage.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace dropcheck {

struct CommandSpec;

inline constexpr int kExitOk = 0;
inline constexpr int kExitCheckFailed = 1;
inline constexpr int kExitBadInput = 2;

// Runs one command; `argv` excludes the program name. Never throws.
int cli_main(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err);

// The commands, each in its own file (cmd_*.cpp). They may throw InputError (exit 2) and
// HelpRequested (the --help text, exit 0).
int cmd_engines(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err);
int cmd_run(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err);
int cmd_bless(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err);
int cmd_diff(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err);
int cmd_check(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err);
int cmd_report(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err);
int cmd_stability(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err);
int cmd_identify(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err);
int cmd_plan(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err);
int cmd_sweep(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err);
int cmd_merge(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err);

// Each command's arguments (harness/cli/args.hpp), defined beside the command.
const CommandSpec& engines_spec();
const CommandSpec& run_spec();
const CommandSpec& bless_spec();
const CommandSpec& diff_spec();
const CommandSpec& check_spec();
const CommandSpec& report_spec();
const CommandSpec& stability_spec();
const CommandSpec& identify_spec();
const CommandSpec& plan_spec();
const CommandSpec& sweep_spec();
const CommandSpec& merge_spec();

}  // namespace dropcheck
