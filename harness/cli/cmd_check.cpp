// dropcheck check PATH... [--engine E]...  (PATH: a scene file, or a folder: the *.toml in it)
// Runs every check that applies to each scene on each engine (harness/study/checks.hpp) and
// prints one line per check: PASS/LIMIT/FAIL (LIMIT: passed, the engine met a limit of its own
// law or design, named), scene, engine, check, measured figures. Exit 1 if any check
// failed. An engine that cannot run a scene is printed as "skipped: <reason>" (ctest reports it
// skipped).
#include "args.hpp"
#include "cli.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/scene/scene_files.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/checks.hpp"
#include "selection.hpp"

namespace dropcheck {
namespace {

EngineFactory factory(const std::string& name) {
  return [name] { return make_engine(name); };
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
        true}}};
  return spec;
}

int cmd_check(const std::vector<std::string>& argv, std::ostream& out, std::ostream&) {
  const Args args = parse_args(check_spec(), argv);
  std::vector<Scene> scenes;
  for (const std::string& file : scene_files(args.positional)) scenes.push_back(load_scene(file));
  if (!make_engine("ours-f64"))
    throw InputError("", 0, "ours-f64", "the reference engine is missing");

  int failed = 0, passed = 0;
  for (const Scene& scene : scenes) {
    for (const SelectedEngine& e : select_engines(args.values("--engine"), scene)) {
      if (!e.engine) {
        out << "skipped: " << scene.name << "  " << e.name << ": " << e.skipped_because << "\n";
        continue;
      }
      for (const CheckResult& r : check_scene(scene, factory(e.name), factory("ours-f64"))) {
        print(r, out);
        (r.passed ? passed : failed)++;
      }
    }
  }
  out << passed << " checks passed, " << failed << " failed\n";
  return failed ? kExitCheckFailed : kExitOk;
}

}  // namespace dropcheck
