// dropcheck plan SWEEP --out PLAN: a sweep file resolved into a plan any machine can run a share
// of.
#include "args.hpp"
#include "cli.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/io/output_plan.hpp"
#include "harness/plan/plan.hpp"

namespace dropcheck {

const CommandSpec& plan_spec() {
  static const CommandSpec spec{
      "plan",
      "Resolves a sweep file (docs/sweeps.md) into a plan: its scenes' texts, engines, axes and "
      "measures, and a hash of all of it. The cells are every scene x engine x axis value; each "
      "has a key, and a shard of N is chosen by a hash of that key alone. Every axis value is "
      "tried on every scene first: one that cannot apply is refused here, before any cell runs.",
      "SWEEP",
      "the sweep file (.toml)",
      1,
      1,
      {{"--out", "PLAN", "where to write the plan (JSON)"},
       {"--keys", "", "also print every cell's key, in plan order"}}};
  return spec;
}

int cmd_plan(const std::vector<std::string>& argv, std::ostream& out, std::ostream&) {
  const Args args = parse_args(plan_spec(), argv);
  const std::string target = args.value("--out");
  if (target.empty()) throw InputError("", 0, "--out", "required: where to write the plan");
  const SweepSpec sweep = load_sweep(args.positional[0], known_engine_names());
  OutputPlan files;  // the plan lands on neither the sweep file nor a scene it names
  files.read(sweep.file);
  for (const std::string& f : sweep.scene_files) files.read(f);
  for (const ExternalEngine& e : sweep.external)
    if (!e.file.starts_with("exec:")) files.read(e.file);
  files.write_file("--out", target);
  files.check();
  std::vector<EngineInfo> engines;  // the sweep's engines this build has, for the run limits
  for (const std::string& name : sweep.engines)
    if (const std::unique_ptr<Engine> e = make_engine(name)) engines.push_back(e->info());
  const Plan plan = make_plan(sweep, engines);
  const std::string text = plan_text(plan);
  if (static_cast<long long>(text.size()) > kMaxPlanBytes)  // every sweep would refuse it
    throw InputError(sweep.file, 0, "",
                     "the plan would take " + std::to_string(text.size()) +
                         " bytes, more than the " + std::to_string(kMaxPlanBytes) +
                         " a sweep reads: split the sweep (fewer scenes, axes or values)");
  write_file_atomic(target, text);
  out << "plan " << plan.hash << ": " << plan.cell_count() << " cells (" << plan.scenes.size()
      << " scenes x " << plan.engines.size() << " engines";
  for (const Axis& a : plan.axes) out << " x " << a.values.size() << " " << a.name;
  out << ") -> " << target << "\n";
  if (args.has("--keys"))
    for (std::size_t i = 0; i < plan.cell_count(); ++i) out << plan.cell(i).key << "\n";
  return kExitOk;
}

}  // namespace dropcheck
