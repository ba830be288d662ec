// dropcheck run FILE [--engine E]... [--dt H] [--csv OUT] [--json OUT]
// Runs the scene on each engine and prints a summary: final state per engine and body, steps,
// wall time, status. Every output path is checked before any engine runs
// (harness/io/output_plan.hpp); output files are written only after every run finished,
// atomically.

#include <algorithm>

#include "args.hpp"
#include "cli.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/io/output_plan.hpp"
#include "harness/io/trajectory_io.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"
#include "selection.hpp"

namespace dropcheck {
namespace {

// The widths of the name columns of `run`'s table: each as wide as its widest name, so that a long
// engine or body name never shifts the figures after it.
struct NameWidths {
  int engine = 6, body = 4;  // "engine", "body"
};

NameWidths name_widths(const Scene& s, const std::vector<SelectedEngine>& engines) {
  NameWidths w;
  for (const SelectedEngine& e : engines)  // a run is named by its engine's own name
    w.engine = std::max(w.engine, int((e.engine ? e.engine->info().name : e.name).size()));
  for (const Body& b : s.bodies) w.body = std::max(w.body, int(b.name.size()));
  return w;
}

void print_header(const Scene& s, const Timestep& dt, const NameWidths& w, std::ostream& out) {
  out << printf_string(
      "scene %s: %zu bodies, %g s at h = %s (%lld steps), gravity (%g, %g, %g), "
      "damping k = %.6g 1/s, contacts %s\n",
      s.name.c_str(), s.bodies.size(), s.duration, dt.text.c_str(),
      static_cast<long long>(step_count(s, dt.seconds)), s.world.gravity.x(), s.world.gravity.y(),
      s.world.gravity.z(), s.world.damping_rate, s.world.contacts ? "on" : "off");
  out << printf_string("%-*s %-*s %13s %13s %13s %12s %12s %12s %8s %9s  %s\n", w.engine, "engine",
                       w.body, "body", "x", "y", "z", "vx", "vy", "vz", "steps", "wall ms",
                       "status");
}

void print_run(const Trajectory& t, const NameWidths& w, std::ostream& out) {
  if (t.samples() == 0) {  // the engine failed before step 0 (load): no state to print
    out << t.engine << "  " << to_string(t.status) << ": " << t.failure << "\n";
    return;
  }
  for (std::size_t b = 0; b < t.bodies(); ++b) {
    const BodyState& s = t.final_state(b);
    std::string status = to_string(t.status);
    if (t.status != RunStatus::ok) status += ": " + t.failure;
    if (t.clamped_steps)
      status += " (speed clamped on " + std::to_string(t.clamped_steps) + " steps)";
    out << printf_string("%-*s %-*s %13.6f %13.6f %13.6f %12.6f %12.6f %12.6f %8lld %9.3f  %s\n",
                         w.engine, t.engine.c_str(), w.body, t.body_names[b].c_str(),
                         s.position.x(), s.position.y(), s.position.z(), s.velocity.x(),
                         s.velocity.y(), s.velocity.z(), static_cast<long long>(t.recorded.back()),
                         t.wall_seconds * 1e3, status.c_str());
  }
}

// True, with the reason on `err`, when no engine ran the scene to its end: every one failed
// (error, crash, time-out, out of memory, refused) or was skipped. A blow-up to NaN is a result of
// the engine's own physics, not a failure of the run.
bool every_engine_failed(const std::vector<Trajectory>& runs, std::ostream& err) {
  for (const Trajectory& t : runs)
    if (t.status == RunStatus::ok || t.status == RunStatus::non_finite) return false;
  err << "dropcheck run: no engine ran the scene to its end: every one failed or was skipped\n";
  return true;
}

}  // namespace

const CommandSpec& run_spec() {
  static const CommandSpec spec{
      "run",
      "Runs the scene on each engine and prints the final state of every body.",
      "scene FILE",
      "the scene file (.toml)",
      1,
      1,
      {{"--engine", "E", "an engine to run (repeatable; default: every engine compiled in)", true},
       {"--dt", "H", "the step: seconds (0.01) or a rate (1/120); default: the scene's"},
       {"--csv", "OUT", "write every sample to OUT as CSV"},
       {"--json", "OUT", "write every sample to OUT as JSON"}}};
  return spec;
}

int cmd_run(const std::vector<std::string>& argv, std::ostream& out, std::ostream& err) {
  const Args args = parse_args(run_spec(), argv);
  OutputPlan plan;
  plan.read(args.positional[0]);
  for (const char* key : {"--csv", "--json"})
    if (args.has(key)) plan.write_file(key, args.value(key));
  plan.check();
  const Scene scene = load_scene(args.positional[0]);
  const Timestep dt = step_from_flag(args.value("--dt"), scene);
  std::vector<SelectedEngine> engines = select_engines(args.values("--engine"), scene);

  const NameWidths widths = name_widths(scene, engines);
  print_header(scene, dt, widths, out);
  std::vector<Trajectory> runs;
  for (SelectedEngine& e : engines) {
    if (!e.engine) {
      out << e.name << "  skipped: " << e.skipped_because << "\n";
      continue;
    }
    runs.push_back(run_scene(*e.engine, scene, dt.seconds));
    print_run(runs.back(), widths, out);
  }
  // Both streamed: memory is the trajectories plus a 64 KiB buffer.
  if (args.has("--csv"))
    write_file_atomic(args.value("--csv"),
                      [&](std::ostream& o) { write_trajectories_csv(o, runs); });
  if (args.has("--json"))
    write_file_atomic(args.value("--json"),
                      [&](std::ostream& o) { write_trajectories_json(o, runs); });
  return every_engine_failed(runs, err) ? kExitCheckFailed : kExitOk;
}

}  // namespace dropcheck
