// dropcheck stability FILE [--engine E]... [--json OUT]
// Classifies each engine at the scene's step (stable, or its failure with a sentence), searches its
// largest stable step by bisection on h, and prints a table; --json writes the study atomically.
// Failures are results: the exit code is 0 unless the input is bad (2).
#include "args.hpp"
#include "cli.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/io/output_plan.hpp"
#include "harness/report/stability_io.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/stability_study.hpp"
#include "selection.hpp"

namespace dropcheck {

const CommandSpec& stability_spec() {
  static const CommandSpec spec{
      "stability",
      "Classifies each engine at the scene's step and searches its largest stable step.",
      "scene FILE",
      "the scene file (.toml)",
      1,
      1,
      {{"--engine", "E", "an engine to study (repeatable; default: every engine compiled in)",
        true},
       {"--json", "OUT", "write the study to OUT as JSON"}}};
  return spec;
}

int cmd_stability(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  const Args args = parse_args(stability_spec(), argv);
  OutputPlan plan;
  plan.read(args.positional[0]);
  if (args.has("--json")) plan.write_file("--json", args.value("--json"));
  plan.check();
  const Scene scene = load_scene(args.positional[0]);
  std::vector<EngineSlot> slots;
  for (const SelectedEngine& e : select_engines(args.values("--engine"), scene)) {
    const std::string name = e.name, why = engine_unavailable_reason(name);
    slots.push_back(
        {name, why.empty() ? EngineFactory([name] { return make_engine(name); }) : EngineFactory(),
         why});
  }
  StudyOptions options;
  const SceneStability study = study_scene(scene, slots, options, &err);
  out << stability_to_text(study);
  if (args.has("--json"))
    write_file_atomic(args.value("--json"), stability_to_json(study, options.search_options));
  return kExitOk;
}

}  // namespace dropcheck
