// dropcheck bless [FILE]... [--engine E]... [--out DIR] [--timing]
//   Rewrites the golden baselines (default: every scenarios/*.toml on ours and ours-f64, into
//   tests/baselines/) and refuses, exit 1, when a fresh run fails an oracle check. With --out
//   elsewhere it always writes, a failed tier marked in its file: exit 0 when every tier passed,
//   1 when a file was written with a failed tier.
// dropcheck bless --check FILE... [--engine E]... [--tier T]... [--baselines DIR]
//   Compares this build with the baselines, tier by tier (harness/guard/regression.hpp): exit 0
//   when every tier passed, 1 when one failed, 77 when every tier was skipped (ctest's
//   SKIP_RETURN_CODE).
#include <algorithm>
#include <filesystem>

#include "args.hpp"
#include "cli.hpp"
#include "harness/core/build_id.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/guard/baseline_io.hpp"
#include "harness/guard/bless.hpp"
#include "harness/guard/regression.hpp"
#include "harness/guard/regression_physics.hpp"
#include "harness/io/output_plan.hpp"
#include "harness/scene/scene_loader.hpp"
#include "selection.hpp"

namespace dropcheck {
namespace {

constexpr int kExitSkipped = 77;

// Every *.toml directly in scenarios/ (not in subfolders), sorted.
std::vector<std::string> shipped_scenes() {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("scenarios", ec))
    if (entry.is_regular_file() && entry.path().extension() == ".toml")
      files.push_back(entry.path().string());
  if (ec || files.empty())
    throw InputError("scenarios", 0, "",
                     "no scene files here; run from the source tree or name FILEs");
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<NamedFactory> engines_from(const Args& args) {
  std::vector<std::string> names = args.values("--engine");
  if (names.empty()) names = {"ours", "ours-f64"};
  std::vector<NamedFactory> out;
  for (const std::string& name : names) {
    if (std::string why = engine_unavailable_reason(name); !why.empty())
      throw InputError("", 0, "--engine " + name, why);
    // Named as the engine names itself: an engine file's engine blesses and checks under its own
    // name.
    out.push_back({make_engine(name)->info().name, [name] { return make_engine(name); }});
  }
  std::vector<std::pair<std::string, std::string>> announced;
  for (std::size_t i = 0; i < out.size(); ++i) announced.emplace_back(names[i], out[i].first);
  refuse_name_clashes(announced);
  return out;
}

// One tier on one scene and engine; `now` is made on first use.
TierResult run_tier(Tier tier, const Scene& scene, const NamedFactory& engine,
                    const std::string& dir, std::optional<Baseline>& now) {
  if (tier == Tier::determinism) return check_determinism(scene, engine.second);
  if (!now) now = make_baseline(scene, engine.second);
  const std::string path = baseline_path(dir, scene.name, engine.first);
  if (tier == Tier::physics) {
    const std::optional<Baseline> baseline = read_baseline_if_present(path);
    if (baseline) check_baseline_claims(*baseline, *now, path);
    return check_physics(*now, baseline ? &*baseline : nullptr,
                         core_checks(scene, engine.second, [] { return make_engine("ours-f64"); }),
                         scene.world.contacts);
  }
  const std::string name = scene.name + " / " + engine.first + " / " + to_string(tier) + ": ";
  if (!now->skipped.empty())
    return {TierVerdict::skipped, name + "the engine cannot run this scene: " + now->skipped};
  const std::optional<Baseline> expected = read_baseline_if_present(path);
  if (!expected)
    return {TierVerdict::failed, name + "no baseline " + path + "; run `dropcheck bless " +
                                     scene.source + "` to make one"};
  check_baseline_claims(*expected, *now, path);
  return tier == Tier::bits ? check_bits(*expected, *now) : check_tolerance(*expected, *now);
}

std::vector<Tier> tiers_from(const Args& args) {
  std::vector<Tier> tiers;
  for (const std::string& name : args.values("--tier")) {
    const std::optional<Tier> t = parse_tier(name);
    if (!t)
      throw InputError("", 0, "--tier " + name, "expected bits, tolerance, physics or determinism");
    tiers.push_back(*t);
  }
  if (tiers.empty()) tiers = {Tier::bits, Tier::tolerance, Tier::physics, Tier::determinism};
  return tiers;
}

// What to do about failed checks (docs/regression.md walks through both cases).
const char* next_step(bool physics_failed) {
  return physics_failed
             ? "the run breaks an oracle: fix the integrator, or declare its new law in its "
               "adapter; `dropcheck bless` refuses until then (docs/regression.md)"
             : "if the change is intended, run `dropcheck bless` and commit tests/baselines/ "
               "(docs/regression.md)";
}

int check(const Args& args, const std::vector<Scene>& scenes, std::ostream& out) {
  const std::vector<Tier> tiers = tiers_from(args);
  const std::string dir = args.value("--baselines", "tests/baselines");
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError(dir, 0, "--baselines", "does not exist or is not a folder of baselines");
  int failed = 0, skipped = 0, total = 0, physics_failed = 0;
  for (const Scene& scene : scenes) {
    for (const NamedFactory& engine : engines_from(args)) {
      std::optional<Baseline> now;
      for (Tier tier : tiers) {
        const TierResult r = run_tier(tier, scene, engine, dir, now);
        out << to_string(r.verdict) << ": " << r.message << "\n";
        failed += r.verdict == TierVerdict::failed;
        physics_failed += r.verdict == TierVerdict::failed && tier == Tier::physics;
        skipped += r.verdict == TierVerdict::skipped;
        ++total;
      }
    }
  }
  if (failed)
    out << failed << " of " << total << " regression checks FAILED; "
        << next_step(physics_failed > 0) << "\n";
  return failed ? kExitCheckFailed : skipped == total ? kExitSkipped : kExitOk;
}

// Before any engine runs: --out is a folder dropcheck may write in, no two baselines share a file
// (bless.hpp), and no baseline lands on a scene file.
void check_outputs(const Args& args, const std::vector<std::string>& files,
                   const std::vector<Scene>& scenes) {
  const std::string dir = args.value("--out", "tests/baselines");
  OutputPlan plan;
  plan.write_into("--out", dir);
  for (const std::string& f : files) plan.read(f);
  std::vector<std::string> engines = args.values("--engine");
  if (engines.empty()) engines = {"ours", "ours-f64"};
  for (const std::string& path : baseline_paths(scenes, engines, dir))
    plan.write_entry("--out", path);  // a link planted in the folder is refused, not followed
  plan.check();
}

int write(const Args& args, const std::vector<Scene>& scenes, std::ostream& out,
          std::ostream& err) {
  BlessOptions options;
  options.out_dir = args.value("--out", "tests/baselines");
  options.commit = source_commit();
  options.reference = [] { return make_engine("ours-f64"); };
  options.baseline.timing = args.has("--timing");
  const BlessOutcome outcome = bless(scenes, engines_from(args), options);
  for (const std::string& why : outcome.refused) err << "dropcheck bless: refused: " << why << "\n";
  if (!outcome.refused.empty()) {
    err << "dropcheck bless: nothing written: a baseline that fails an oracle check would make "
           "wrong "
           "physics the truth. Fix the integrator, or the law its adapter declares.\n";
    return kExitCheckFailed;
  }
  for (const std::string& line : outcome.lines) out << line << "\n";
  for (const std::string& why : outcome.failed)
    err << "dropcheck bless: FAILED (written, marked in the file): " << why << "\n";
  return outcome.failed.empty() ? kExitOk : kExitCheckFailed;
}

}  // namespace

const CommandSpec& bless_spec() {
  static const CommandSpec spec{
      "bless",
      "Rewrites the golden baselines (refused, exit 1, when a fresh run fails an oracle check); "
      "with --out DIR elsewhere always writes, a failed tier marked in its file (exit 0 every tier "
      "passed, 1 a file was written with a failed tier); or with --check compares this build with "
      "them tier by tier (exit 77 when every tier was skipped).",
      "scene FILE",
      "scene files (default: every scenarios/*.toml)",
      0,
      -1,
      {{"--engine", "E", "an engine (repeatable; default: ours and ours-f64)", true},
       {"--out", "DIR",
        "the folder of baselines to write (default: tests/baselines); elsewhere always written, "
        "exit 1 when a tier failed"},
       {"--timing", "", "record wall-clock timings in the baselines"},
       {"--check", "", "compare with the baselines instead of writing them"},
       {"--tier", "T", "with --check: bits, tolerance, physics or determinism (repeatable)", true},
       {"--baselines", "DIR",
        "with --check: the baselines to compare with (default: tests/baselines)"}}};
  return spec;
}

int cmd_bless(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  const Args args = parse_args(bless_spec(), argv);
  const bool checking = args.has("--check");
  if (checking && (args.has("--out") || args.has("--timing")))
    throw InputError("", 0, "--check", "compares only; --out and --timing belong to blessing");
  if (!checking && (args.has("--tier") || args.has("--baselines")))
    throw InputError("", 0, "--tier/--baselines", "only with --check");
  std::vector<std::string> files = args.positional;
  if (files.empty()) files = shipped_scenes();
  std::vector<Scene> scenes;
  for (const std::string& f : files) scenes.push_back(load_scene(f));
  if (!checking) check_outputs(args, files, scenes);
  return checking ? check(args, scenes, out) : write(args, scenes, out, err);
}

}  // namespace dropcheck
