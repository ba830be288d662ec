// dropcheck report [FILE|DIR]... [--out DIR] [--engine E]... [--reference E] [--no-timing]
// Evaluates every scene on every engine (harness/study/evaluate.hpp) and writes DIR/README.md
// plus SVG plots (harness/report/report.hpp). Default: every *.toml directly in scenarios/; scenes
// in an extreme/ folder go to the stability section (harness/report/stability_report.hpp). Every
// scene file is loaded before any work starts, and the output is built in a staging directory and
// swapped into place only when complete: a bad scene file exits 2 naming the file, key and problem,
// and leaves the previous report untouched. DIR is replaced only when dropcheck wrote it (its
// .dropcheck-manifest, harness/io/output_dir.hpp); that and every other output rule is checked
// before any engine runs. With timings, DIR/timings.json keeps them, and the next report into DIR
// says how far each median moved (the two-run figure of "Timing reproducibility").
#include <algorithm>
#include <filesystem>

#include "args.hpp"
#include "cli.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/registry.hpp"
#include "harness/io/output_dir.hpp"
#include "harness/io/output_plan.hpp"
#include "harness/report/report.hpp"
#include "harness/report/report_sweep.hpp"
#include "harness/report/stability_report.hpp"
#include "harness/report/sweep_results.hpp"
#include "harness/run/forked_text.hpp"
#include "harness/scene/scene_files.hpp"
#include "harness/scene/scene_loader.hpp"
#include "selection.hpp"

namespace fs = std::filesystem;

namespace dropcheck {
namespace {

struct SceneFiles {
  std::vector<std::string> scenes;   // the comparison
  std::vector<std::string> extreme;  // the stability section
};

void add_path(const std::string& arg, SceneFiles& files) {
  const fs::path p(arg);
  std::error_code ec;
  if (fs::is_directory(p, ec)) {
    for (std::string& f : toml_files(arg)) files.scenes.push_back(std::move(f));
    if (fs::is_directory(p / "extreme", ec))
      for (std::string& f : toml_files((p / "extreme").generic_string()))
        files.extreme.push_back(std::move(f));
  } else if (fs::exists(p, ec)) {
    const bool extreme = p.lexically_normal().parent_path().filename() == "extreme";
    (extreme ? files.extreme : files.scenes).push_back(arg);
  } else {
    throw InputError(arg, 0, "", "no such file or directory");
  }
}

SceneFiles report_scene_files(const std::vector<std::string>& args) {
  SceneFiles files;
  for (const std::string& a : args.empty() ? std::vector<std::string>{"scenarios"} : args)
    add_path(a, files);
  if (files.scenes.empty() && files.extreme.empty())
    throw InputError("", 0, "report", "no scene files (*.toml) found");
  return files;
}

// The engines to run: the --engine names given, or every engine dropcheck knows.
std::vector<EngineSlot> engine_slots(const std::vector<std::string>& requested) {
  std::vector<EngineSlot> slots;
  const std::vector<std::string> names = requested.empty() ? known_engine_names() : requested;
  for (const std::string& name : names) {
    const std::string why = engine_unavailable_reason(name);
    if (why.rfind("unknown", 0) == 0)
      throw InputError("", 0, "--engine " + escape_controls(name), why);
    EngineSlot s{name, {}, why};
    if (why.empty()) s.make = [name] { return make_engine(name); };
    if (why.empty())
      s.name = s.make()->info().name;  // an engine file's engine reports under its own name
    slots.push_back(std::move(s));
  }
  std::vector<std::pair<std::string, std::string>> announced;
  for (std::size_t i = 0; i < slots.size(); ++i)
    if (slots[i].make) announced.emplace_back(names[i], slots[i].name);
  refuse_name_clashes(announced);
  return slots;
}

void describe_engines(const std::vector<EngineSlot>& slots, ReportInput& in) {
  for (const EngineSlot& s : slots) {
    if (s.make)
      in.engines.push_back(s.make()->info());
    else
      in.missing.emplace_back(s.name, s.unavailable);
  }
}

// Evaluates each scene, with progress lines "[3/7] wind: bullet 1/120 ..." on `err`; then, unless
// --no-timing, times them all as one schedule ("timing 61 cells: round 2 of 9 ...").
void evaluate_all(const std::vector<Scene>& scenes, const std::vector<EngineSlot>& slots,
                  const EvaluateOptions& options, std::size_t total, ReportInput& in,
                  std::ostream& err) {
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const std::string prefix =
        "[" + std::to_string(i + 1) + "/" + std::to_string(total) + "] " + scenes[i].name + ": ";
    in.scenes.push_back(evaluate_scene(scenes[i], slots, options, [&](const std::string& what) {
      err << prefix << what << " ...\n" << std::flush;
    }));
  }
}

void time_all(const std::vector<EngineSlot>& slots, ReportInput& in, std::ostream& err) {
  if (!in.timing) return;
  time_evaluations(in.scenes, slots, in.timing_options, [&](const std::string& what) {
    err << what << " ...\n" << std::flush;
  });
}

// Prints the cells the slowdown alert flagged and how many it judged; with --fail-on-slowdown,
// kExitCheckFailed when it flagged one, and kExitBadInput when it could judge none (no record, or
// one whose cells do not match this report's): a gate that checked nothing must not pass.
int slowdown_exit(const ReportInput& in, bool fail, std::ostream& err) {
  if (!in.timing) return kExitOk;
  const TimingRecord now = timing_record(in.scenes, in.provenance, in.machine);
  const SlowdownAlert alert = slowdown_alert(in, now);
  if (!alert.before) {
    if (!fail) return kExitOk;
    err << "dropcheck report: --fail-on-slowdown: no timings to compare with (give "
           "--compare-timings FILE); no cell judged\n";
    return kExitBadInput;
  }
  if (!alert.other_machine.empty()) {
    err << "timings: the record compared with (commit " << alert.before->commit
        << ") was measured on another machine (they differ in " << alert.other_machine
        << "): no cell judged; the report says more\n";
    if (!fail) return kExitOk;
    err << "dropcheck report: --fail-on-slowdown: timings from another machine cannot be judged "
           "here; compare with a record written on this machine\n";
    return kExitBadInput;
  }
  for (const Slowdown& s : alert.flagged)
    err << "slowdown: " << s.cell.scene << " / " << s.cell.engine << " / h = " << s.cell.h << ": "
        << to_string(kAlertFigure) << " rose " << printf_string("%.1f %%", 100.0 * s.cell.moved)
        << printf_string(", its engine's median %.1f %% (threshold %.0f %%)",
                         100.0 * s.engine_median, 100.0 * s.threshold)
        << "\n";
  err << "slowdown alert: " << alert.judged << " of " << now.cells.size() << " cells judged, "
      << alert.flagged.size() << " flagged\n";
  if (fail && alert.judged == 0) {
    err << "dropcheck report: --fail-on-slowdown: no cell of this report matches one timed the "
           "same way in the record compared with\n";
    return kExitBadInput;
  }
  return fail && !alert.flagged.empty() ? kExitCheckFailed : kExitOk;
}

}  // namespace

const CommandSpec& report_spec() {
  static const CommandSpec spec{
      "report",
      "Evaluates every scene on every engine and writes a Markdown report with SVG plots.",
      "PATH",
      "scene files or folders of them (default: scenarios)",
      0,
      -1,
      {{"--out", "DIR", "the report folder, replaced whole (default: reports)"},
       {"--engine", "E", "an engine to include (repeatable; default: every engine dropcheck knows)",
        true},
       {"--reference", "E",
        "the engine divergences are measured from, named in every header (default: ours-f64, or "
        "the first engine given when ours-f64 is not; on a scene it does not run, the first "
        "engine that ran it, named in that scene's section)"},
       {"--no-timing", "", "leave out the wall-clock timings"},
       {"--compare-timings", "FILE",
        "the timings.json the slowdown alert compares with (default: the one in --out)"},
       {"--fail-on-slowdown", "",
        "exit 1 when the slowdown alert flags a cell (the report is written all the same)"},
       {"--results", "FILE",
        "instead of running scenes: a sweep's merged results (dropcheck merge), drawn as maps "
        "over its first two axes per scene and engine, with the failed cells"},
       {"--timing-smoke", "",
        "time as little work as possible (2 rounds, no warm-up, the smallest runs): checks the "
        "timing and the alert in seconds; its figures mean nothing"}}};
  return spec;
}

namespace {

// `report --results FILE`: the sweep report, built in a staging folder like the scene report.
int sweep_report(const Args& args, const std::string& out_dir, std::ostream& out,
                 std::ostream& err) {
  if (!args.positional.empty() || args.has("--engine"))
    throw InputError("", 0, "--results", "a sweep report takes no scene files or engines");
  OutputPlan files;
  files.read(args.value("--results"));
  files.write_folder("--out", out_dir);
  files.check();
  const std::vector<SweepCell> cells = read_sweep_results(args.value("--results"));
  StagingDir staging(out_dir);
  write_sweep_report(cells, args.value("--results"), staging.path(),
                     [&](const std::string& what) { err << "report: " << what << " ...\n"; });
  staging.commit();
  out << "wrote " << (fs::path(out_dir) / "README.md").generic_string() << " (" << cells.size()
      << " cells)\n";
  return kExitOk;
}

}  // namespace

int cmd_report(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  const Args args = parse_args(report_spec(), argv);
  const std::string out_dir = args.value("--out", "reports");
  if (args.has("--results")) return sweep_report(args, out_dir, out, err);
  const SceneFiles files = report_scene_files(args.positional);
  OutputPlan plan;
  for (const std::string& f : files.scenes) plan.read(f);
  for (const std::string& f : files.extreme) plan.read(f);
  plan.write_folder("--out", out_dir);
  plan.check();
  std::vector<Scene> scenes;
  for (const std::string& f : files.scenes) scenes.push_back(load_scene(f));
  for (const std::string& f : files.extreme) load_scene(f);  // validated now, run by the section
  const std::vector<EngineSlot> slots = engine_slots(args.values("--engine"));
  EvaluateOptions options;
  options.reference = args.value("--reference", options.reference);
  if (args.has("--reference") && std::none_of(slots.begin(), slots.end(), [&](const EngineSlot& s) {
        return s.name == options.reference && s.make;
      }))
    throw InputError("", 0, "--reference " + options.reference,
                     "not one of the engines this report runs (give it with --engine too, or "
                     "leave out --engine)");
  // Without --reference: ours-f64 when it runs, else the first engine that does.
  if (!args.has("--reference") &&
      std::none_of(slots.begin(), slots.end(),
                   [&](const EngineSlot& s) { return s.name == options.reference && s.make; }))
    for (const EngineSlot& s : slots)
      if (s.make) {
        options.reference = s.name;
        break;
      }

  ReportInput in;
  in.reference = options.reference;
  in.timing = !args.has("--no-timing");
  in.provenance = current_provenance(".", out_dir);
  in.machine = this_machine();
  describe_engines(slots, in);
  if (args.has("--timing-smoke")) {
    in.timing_options.min_run_seconds = 0.0;
    in.timing_options.min_sample_seconds = 0.0;
    in.timing_options.warmups = 0;
    in.timing_options.samples = 2;
  }
  if (!in.timing && (args.has("--compare-timings") || args.has("--fail-on-slowdown") ||
                     args.has("--timing-smoke")))
    throw InputError("", 0, "--compare-timings/--fail-on-slowdown/--timing-smoke",
                     "need the timings: drop --no-timing");
  if (in.timing) {  // the report this one replaces, to say how far each figure moved
    in.previous = read_previous_timings(out_dir);
    if (!in.previous.warning.empty())
      err << "warning: " << in.previous.warning << "; no comparison with the previous report\n";
    if (args.has("--compare-timings"))  // before any work: a bad file is a usage error
      in.compare = {read_timing_record(args.value("--compare-timings")), "", ""};
  }
  const std::size_t total = scenes.size() + (files.extreme.empty() ? 0 : 1);
  // The stability section in a child process on the other core while this one evaluates the
  // scenes; both end before the timing starts, which wants the machine to itself.
  std::optional<ForkedText> stability;
  if (!files.extreme.empty()) {
    err << "[" << total << "/" << total << "] stability: " << files.extreme.size()
        << " extreme scenes, beside the others ...\n";
    stability.emplace([&] { return stability_report_section(files.extreme, slots, err); });
  }
  evaluate_all(scenes, slots, options, total, in, err);
  if (stability) in.stability = stability->get();
  time_all(slots, in, err);

  StagingDir staging(out_dir);
  write_report(in, staging.path(),
               [&](const std::string& what) { err << "report: " << what << " ...\n"; });
  staging.commit();
  out << "wrote " << (fs::path(out_dir) / "README.md").generic_string() << " (" << scenes.size()
      << " scenes)\n";
  return slowdown_exit(in, args.has("--fail-on-slowdown"), err);
}

}  // namespace dropcheck
