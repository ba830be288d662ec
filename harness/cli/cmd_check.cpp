// dropcheck check PATH... [--engine E]... [--junit FILE] [--json FILE]  (PATH: a scene file, or a
// folder: the *.toml in it)
// Runs every check that applies to each scene on each engine (harness/study/checks.hpp) and
// prints one line per check: PASS/LIMIT/FAIL (LIMIT: passed, the engine met a limit of its own
// law or design, named), scene, engine, check, measured figures. Exit 1 if any check
// failed. An engine that cannot run a scene is printed as "skipped: <reason>" (ctest reports it
// skipped). --junit and --json write the same verdicts for CI (harness/report/verdict_files.hpp),
// each replaced atomically once every check has run. With one --engine, a page of that engine
// alone ends the output: each scene passed, failed (its first failing check) or skipped (with the
// capability that would let it run).
#include "args.hpp"
#include "cli.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/io/output_plan.hpp"
#include "harness/report/verdict_files.hpp"
#include "harness/scene/scene_files.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/checks.hpp"
#include "selection.hpp"

namespace dropcheck {
namespace {

EngineFactory factory(const std::string& name) {
  return [name] { return make_engine(name); };
}

// One engine alone (`--engine X` given once): its scenes passed, failed with the first failing
// check and its cause, skipped with the capability that would let it run them.
void print_engine_page(const std::vector<CheckRecord>& records, const std::string& engine,
                       std::ostream& out) {
  const std::vector<SceneOutcome> outcomes = engine_outcomes(records, engine);
  int passed = 0, failed = 0, skipped = 0;
  for (const SceneOutcome& o : outcomes)
    (o.verdict == "passed" ? passed : o.verdict == "failed" ? failed : skipped)++;
  out << "\n"
      << engine << " alone: " << outcomes.size() << " scenes, " << passed << " passed, " << failed
      << " failed, " << skipped << " skipped\n";
  for (const SceneOutcome& o : outcomes) {
    out << "  " << o.verdict << std::string(9 - o.verdict.size(), ' ') << o.scene;
    if (o.verdict == "passed") out << " (" << o.checks << (o.checks == 1 ? " check)" : " checks)");
    if (!o.detail.empty()) out << ": " << o.detail;
    if (!o.capability.empty())
      out << " (declare the capability `" << o.capability
          << "` to run it, if the engine can: docs/protocol.md)";
    out << "\n";
  }
}

void print(const CheckResult& r, std::ostream& out) {
  const char* verdict = !r.passed ? "FAIL  " : r.limit.empty() ? "PASS  " : "LIMIT ";
  out << verdict << r.scene << "  " << r.engine << "  " << r.check << ": "
      << (r.limit.empty() ? "" : r.limit + "; ") << r.message << "\n";
}

}  // namespace

const CommandSpec& check_spec() {
  static const CommandSpec spec{
      "check",
      "Runs every check that applies to each scene on each engine; exit 1 if one failed.",
      "PATH",
      "scene files (.toml), or folders: the *.toml directly in each",
      1,
      -1,
      {{"--engine", "E", "an engine to check (repeatable; default: every engine compiled in)",
        true},
       {"--junit", "FILE", "also write the verdicts as JUnit XML, one test case a check"},
       {"--json", "FILE", "also write the verdicts as JSON (docs/check.schema.json)"}}};
  return spec;
}

int cmd_check(const std::vector<std::string>& argv, std::ostream& out, std::ostream&) {
  const Args args = parse_args(check_spec(), argv);
  OutputPlan plan;
  for (const std::string& path : args.positional) plan.read(path);
  for (const char* key : {"--junit", "--json"})
    if (args.has(key)) plan.write_file(key, args.value(key));
  plan.check();
  std::vector<Scene> scenes;
  for (const std::string& file : scene_files(args.positional)) scenes.push_back(load_scene(file));
  if (!make_engine("ours-f64"))
    throw InputError("", 0, "ours-f64", "the reference engine is missing");

  int failed = 0, passed = 0;
  std::vector<CheckRecord> records;
  for (const Scene& scene : scenes) {
    for (const SelectedEngine& e : select_engines(args.values("--engine"), scene)) {
      if (!e.engine) {
        out << "skipped: " << scene.name << "  " << e.name << ": " << e.skipped_because << "\n";
        CheckRecord skip;
        skip.result.scene = scene.name;
        skip.result.engine = e.name;
        skip.skipped = true;
        skip.skipped_because = e.skipped_because;
        records.push_back(std::move(skip));
        continue;
      }
      for (const CheckResult& r : check_scene(scene, factory(e.name), factory("ours-f64"))) {
        print(r, out);
        (r.passed ? passed : failed)++;
        CheckRecord record;
        record.result = r;
        records.push_back(std::move(record));
      }
    }
  }
  out << passed << " checks passed, " << failed << " failed\n";
  if (args.values("--engine").size() == 1 && !records.empty())
    print_engine_page(records, records.front().result.engine, out);
  if (args.has("--junit"))
    write_file_atomic(args.value("--junit"), [&](std::ostream& o) { write_junit(o, records); });
  if (args.has("--json"))
    write_file_atomic(args.value("--json"), [&](std::ostream& o) { write_check_json(o, records); });
  return failed ? kExitCheckFailed : kExitOk;
}

}  // namespace dropcheck
