#include "cli.hpp"

#include <exception>

#include "args.hpp"
#include "harness/core/input_error.hpp"

namespace dropcheck {
namespace {

using Command = int (*)(const std::vector<std::string>&, std::ostream&, std::ostream&);

struct CommandEntry {
  const char* name;
  Command run;
  const char* usage;
};

const CommandEntry kCommands[] = {
    {"engines", cmd_engines, "dropcheck engines"},
    {"run", cmd_run, "dropcheck run FILE [--engine E]... [--dt H] [--csv OUT] [--json OUT]"},
    {"bless", cmd_bless,
     "dropcheck bless [FILE]... [--engine E]... [--out DIR] [--timing]\n"
     "  dropcheck bless --check FILE... [--engine E]... [--tier T]... [--baselines DIR]"},
    {"diff", cmd_diff, "dropcheck diff OLD NEW [--out FILE]"},
    {"check", cmd_check, "dropcheck check PATH... [--engine E]..."},
    {"report", cmd_report,
     "dropcheck report [FILE|DIR]... [--out DIR] [--engine E]... [--no-timing]"},
    {"stability", cmd_stability, "dropcheck stability FILE [--engine E]... [--json OUT]"},
    {"identify", cmd_identify, "dropcheck identify FILE (--engine E [--dt H] | --trajectory CSV)"},
    {"plan", cmd_plan, "dropcheck plan SWEEP --out PLAN [--keys]"},
    {"sweep", cmd_sweep,
     "dropcheck sweep PLAN (--shard I/N | --cells-from FILE) --out DIR [--cache DIR] [--quiet]"},
    {"merge", cmd_merge, "dropcheck merge PLAN DIR --out RESULTS [--missing FILE]"},
};

void usage(std::ostream& err) {
  err << "usage:\n";
  for (const CommandEntry& c : kCommands) err << "  " << c.usage << "\n";
  err << "Run `dropcheck COMMAND --help` for a command's options. Exit codes: 0 ok, 1 a check "
         "failed, 2 bad input or usage.\n";
}

}  // namespace

int cli_main(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  if (argv.empty() || argv[0] == "--help" || argv[0] == "-h") {
    usage(argv.empty() ? err : out);
    return argv.empty() ? kExitBadInput : kExitOk;
  }
  for (const CommandEntry& c : kCommands) {
    if (argv[0] != c.name) continue;
    try {
      return c.run({argv.begin() + 1, argv.end()}, out, err);
    } catch (const HelpRequested& h) {
      out << h.text;
      return kExitOk;
    } catch (const InputError& e) {
      err << "dropcheck " << c.name << ": " << e.what() << "\n";
      return kExitBadInput;
    } catch (const std::exception& e) {
      err << "dropcheck " << c.name << ": internal error: " << e.what() << "\n";
      return kExitBadInput;
    }
  }
  err << "dropcheck: unknown command '" << argv[0] << "'\n";
  usage(err);
  return kExitBadInput;
}

}  // namespace dropcheck
