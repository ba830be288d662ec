// dropcheck diff OLD NEW [--out FILE]
// Compares two result sets (directories of baseline files: tests/baselines/, or what
// `dropcheck bless --out DIR` wrote) and prints a Markdown summary (harness/guard/result_diff.hpp) to
// stdout or, atomically, to FILE. Exit 0 whatever moved: it reports, it does not judge.
#include "args.hpp"
#include "cli.hpp"
#include "harness/core/atomic_file.hpp"
#include "harness/core/input_error.hpp"
#include "harness/guard/result_diff.hpp"

namespace dropcheck {

int cmd_diff(const std::vector<std::string>& argv, std::ostream& out, std::ostream&) {
  const Args args = parse_args(argv, {"--out"}, {});
  if (args.positional.size() != 2) throw InputError("", 0, "diff", "expects two result sets: OLD NEW");
  const std::string markdown =
      diff_markdown(load_result_set(args.positional[0]), load_result_set(args.positional[1]));
  if (args.has("--out")) {
    write_file_atomic(args.value("--out"), markdown);
  } else {
    out << markdown;
  }
  return kExitOk;
}

}  // namespace dropcheck
