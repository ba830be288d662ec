// dropcheck diff OLD NEW [--out FILE]
// Compares two result sets (directories of baseline files: tests/baselines/, or what
// `dropcheck bless --out DIR` wrote) and prints a Markdown summary (harness/guard/result_diff.hpp)
// to stdout or, atomically, to FILE. Exit 0 whatever moved: it reports, it does not judge; 2 when a
// folder holds no baseline file, or --out would land on or inside OLD or NEW.
#include "args.hpp"
#include "cli.hpp"
#include "harness/core/input_error.hpp"
#include "harness/guard/result_diff.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/io/output_plan.hpp"

namespace dropcheck {

namespace {

// A result set that holds at least one baseline file: an empty or unrelated folder is bad input.
ResultSet load_nonempty(const std::string& dir) {
  ResultSet set = load_result_set(dir);
  if (set.runs.empty())
    throw InputError(dir, 0, "",
                     "holds no baseline files (*.txt written by `dropcheck bless --out DIR`)");
  return set;
}

}  // namespace

const CommandSpec& diff_spec() {
  static const CommandSpec spec{
      "diff",
      "Compares two result sets (folders of baseline files) and prints a Markdown summary.",
      "result sets OLD NEW",
      "folders of baseline files",
      2,
      2,
      {{"--out", "FILE", "write the summary to FILE instead"}}};
  return spec;
}

int cmd_diff(const std::vector<std::string>& argv, std::ostream& out, std::ostream&) {
  const Args args = parse_args(diff_spec(), argv);
  OutputPlan plan;
  plan.read(args.positional[0]);
  plan.read(args.positional[1]);
  if (args.has("--out")) plan.write_file("--out", args.value("--out"));
  plan.check();
  const ResultSet before = load_nonempty(args.positional[0]);  // OLD first: its errors come first
  const ResultSet after = load_nonempty(args.positional[1]);
  const std::string markdown = diff_markdown(before, after);
  if (args.has("--out")) {
    write_file_atomic(args.value("--out"), markdown);
  } else {
    out << markdown;
  }
  return kExitOk;
}

}  // namespace dropcheck
