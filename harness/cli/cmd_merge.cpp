// dropcheck merge PLAN DIR --out RESULTS: a plan's shard files into one result file.
#include <filesystem>

#include "args.hpp"
#include "cli.hpp"
#include "harness/core/input_error.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/io/output_plan.hpp"
#include "harness/plan/merge.hpp"

namespace dropcheck {

const CommandSpec& merge_spec() {
  static const CommandSpec spec{
      "merge",
      "Merges the shard files in DIR into RESULTS: every record of the plan once, sorted by key, "
      "the same bytes however the plan was split. A record of another plan, or one cell recorded "
      "twice with different bytes, is an error naming the files (2). When cells are missing, "
      "their keys are written to --missing (default RESULTS.missing), RESULTS is not written, and "
      "the exit code is 1: `dropcheck sweep PLAN --cells-from RESULTS.missing --out DIR` runs "
      "them.",
      "PLAN DIR",
      "the plan file and the folder of its shard files",
      2,
      2,
      {{"--out", "RESULTS", "where to write the merged records (JSON lines)"},
       {"--missing", "FILE", "where to list missing cells (default RESULTS.missing)"}}};
  return spec;
}

int cmd_merge(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  const Args args = parse_args(merge_spec(), argv);
  const std::string target = args.value("--out");
  if (target.empty()) throw InputError("", 0, "--out", "required: where to write the results");
  const std::string missing = args.value("--missing", target + ".missing");
  OutputPlan files;  // neither output lands on the plan, in the shard folder, or on the other
  files.read(args.positional[0]);
  files.read(args.positional[1]);
  files.write_file("--out", target);
  files.write_file("--missing", missing);
  files.check();
  const Plan plan = read_plan(args.positional[0]);
  const MergeResult m = merge_shards(plan, args.positional[1], target);
  if (m.missing.empty()) {
    // A list of missing cells from an earlier merge of the same results is stale now.
    std::error_code ec;
    if (!args.has("--missing") &&
        std::filesystem::is_regular_file(std::filesystem::symlink_status(missing, ec)))
      std::filesystem::remove(missing, ec);
    out << "merge " << plan.hash << ": " << m.records << " records from " << m.files << " files -> "
        << target << "\n";
    return kExitOk;
  }
  std::string list;
  for (const std::string& k : m.missing) list += k + "\n";
  write_file_atomic(missing, list);
  err << "merge " << plan.hash << ": " << m.missing.size() << " of " << plan.cell_count()
      << " cells missing (listed in " << missing << "); " << target << " not written\n";
  return kExitCheckFailed;
}

}  // namespace dropcheck
