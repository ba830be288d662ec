// dropcheck sweep PLAN (--shard I/N | --cells-from FILE) --out DIR: runs a share of a plan.
#include <filesystem>
#include <iostream>

#include "args.hpp"
#include "cli.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/io/output_plan.hpp"
#include "harness/plan/shard.hpp"
#include "harness/plan/worker.hpp"

namespace dropcheck {

// More workers than this is a mistake, not a machine.
inline constexpr int kMaxJobs = 1024;

const CommandSpec& sweep_spec() {
  static const CommandSpec spec{
      "sweep",
      "Runs shard I of N of a plan (the cells whose key hashes to it) or the cells a file lists "
      "(one key per line, as `dropcheck merge` writes the missing ones), and writes their records "
      "(docs/results.md) to DIR/shard-I-of-N.jsonl or DIR/cells-HASH.jsonl, whole or not at all. "
      "An engine that fails, blows up or hangs in a cell is that cell's record: the exit code is "
      "0 unless the sweep itself could not run (2).",
      "PLAN",
      "the plan file (dropcheck plan)",
      1,
      1,
      {{"--shard", "I/N", "run shard I of N (1 <= I <= N)"},
       {"--cells-from", "FILE", "run the cells FILE lists instead"},
       {"--out", "DIR", "the folder of shard files (created when missing)"},
       {"--cache", "DIR", "reuse records this build made for the same cells (in any plan)"},
       {"--jobs", "J",
        "run J cells side by side (default: every core this process may use, as its CPU "
        "affinity says: what a Slurm task or taskset gives it)"},
       {"--engine-file", "FILE",
        "an engine file (NAME.toml) or exec:PATH the plan names (repeatable): a plan never starts "
        "a program by itself, and each is checked against the fingerprint it was planned with",
        true},
       {"--quiet", "", "no progress line per cell"}}};
  return spec;
}

namespace {

// Each external engine of the plan authorised by an --engine-file of the same id (the same name
// and fingerprint), before any cell runs.
void authorise_external(Plan& plan, const Args& args) {
  for (const std::string& f : args.values("--engine-file")) {
    const std::string key = "--engine-file " + excerpt(f);
    const std::optional<ExternalEngineId> id = external_engine_id(f);
    if (!id) throw InputError("", 0, key, "not an engine file (NAME.toml) or exec:PATH");
    const auto named = [&](const std::string& prefix) {
      return std::find_if(plan.external.begin(), plan.external.end(),
                          [&](const ExternalEngine& e) { return e.id.starts_with(prefix); });
    };
    const auto e = named(id->id());
    if (e != plan.external.end()) {
      e->runs = f;
      continue;
    }
    const auto same_name = named(id->name + "@");
    throw InputError(
        "", 0, key,
        same_name == plan.external.end()
            ? id->id() + " is not an engine of plan " + plan.hash
            : "is " + id->id() + " now, and the plan has " + same_name->id +
                  ": the engine file or what it runs changed since `dropcheck plan` (plan the "
                  "sweep again: a changed engine is another engine, with other cells)");
  }
  for (const ExternalEngine& e : plan.external)
    if (e.runs.empty())
      throw InputError("", 0, "--engine-file",
                       "plan " + plan.hash + " runs the external engine " + e.id +
                           (e.file.empty() ? "" : " (planned from " + excerpt(e.file) + ")") +
                           ": a plan never starts a program by itself; give its engine file with "
                           "--engine-file");
}

}  // namespace

int cmd_sweep(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  const Args args = parse_args(sweep_spec(), argv);
  const std::string dir = args.value("--out");
  if (dir.empty()) throw InputError("", 0, "--out", "required: the folder of shard files");
  if (args.has("--shard") == args.has("--cells-from"))
    throw InputError("", 0, "--shard", "give either --shard I/N or --cells-from FILE");
  int jobs = usable_cores();
  if (args.has("--jobs")) {
    const std::string j = args.value("--jobs");
    std::size_t used = 0;
    int parsed = 0;
    try {
      parsed = std::stoi(j, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != j.size() || parsed < 1 || parsed > kMaxJobs)
      throw InputError("", 0, "--jobs",
                       "expected a whole number of workers from 1 to " + std::to_string(kMaxJobs) +
                           ", got " + excerpt(j));
    jobs = parsed;
  }
  Plan plan = read_plan(args.positional[0]);
  authorise_external(plan, args);
  std::vector<std::size_t> cells;
  std::string name;
  if (args.has("--shard")) {
    const ShardSpec s = parse_shard(args.value("--shard"));
    cells = cells_of_shard(plan, s);
    name = shard_file_name(s);
  } else {
    cells = cells_from(plan, args.value("--cells-from"), name);
  }
  // Where the records go, settled before any cell runs: a folder (made when missing), and in it a
  // shard file or nothing, never a link, never an input; the cache a folder too (its entries are
  // checked for links at every depth by run_cells, before the first cell runs).
  const std::string target = (std::filesystem::path(dir) / name).string();
  OutputPlan files;
  files.read(args.positional[0]);
  if (args.has("--cells-from")) files.read(args.value("--cells-from"));
  for (const std::string& f : args.values("--engine-file"))
    if (!f.starts_with("exec:")) files.read(f);
  files.write_into("--out", dir);
  files.write_entry("--out", target);
  if (args.has("--cache")) files.write_into("--cache", args.value("--cache"));
  files.check();
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError("", 0, "--out", excerpt(dir) + " is not a folder and cannot be made one");
  std::ostream null_stream(nullptr);
  const ShardSummary s = run_cells(plan, cells, target, args.has("--quiet") ? null_stream : err,
                                   args.value("--cache"), jobs);
  out << "sweep " << plan.hash << ": " << s.cells << " cells (" << s.ok << " ok, " << s.failed
      << " not ok, " << s.skipped << " skipped";
  if (args.has("--cache")) out << "; " << s.cached << " from the cache";
  out << ") -> " << target << "\n";
  return kExitOk;
}

}  // namespace dropcheck
