// dropcheck run FILE [--engine E]... [--dt H] [--csv OUT] [--json OUT]
// Runs the scene on each engine and prints a summary: final state per engine and body, steps,
// wall time, status. Output files are written only after every run finished, atomically.
#include <cstdio>

#include "args.hpp"
#include "cli.hpp"
#include "harness/core/atomic_file.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/runner.hpp"
#include "harness/core/scene_loader.hpp"
#include "harness/core/trajectory_io.hpp"
#include "selection.hpp"

namespace dropcheck {
namespace {

void print_header(const Scene& s, const Timestep& dt, std::ostream& out) {
  char line[256];
  std::snprintf(line, sizeof line,
                "scene %s: %zu bodies, %g s at h = %s (%lld steps), gravity (%g, %g, %g), "
                "damping k = %.6g 1/s, contacts %s\n",
                s.name.c_str(), s.bodies.size(), s.duration, dt.text.c_str(),
                static_cast<long long>(step_count(s, dt.seconds)), s.world.gravity.x(),
                s.world.gravity.y(), s.world.gravity.z(), s.world.damping_rate,
                s.world.contacts ? "on" : "off");
  out << line;
  std::snprintf(line, sizeof line, "%-9s %-10s %13s %13s %13s %12s %12s %12s %8s %9s  %s\n", "engine",
                "body", "x", "y", "z", "vx", "vy", "vz", "steps", "wall ms", "status");
  out << line;
}

void print_run(const Trajectory& t, std::ostream& out) {
  char line[320];
  if (t.samples() == 0) {  // the engine failed before step 0 (load): no state to print
    out << t.engine << "  " << to_string(t.status) << ": " << t.failure << "\n";
    return;
  }
  for (std::size_t b = 0; b < t.bodies(); ++b) {
    const BodyState& s = t.final_state(b);
    std::string status = to_string(t.status);
    if (t.status != RunStatus::ok) status += ": " + t.failure;
    if (t.clamped_steps) status += " (speed clamped on " + std::to_string(t.clamped_steps) + " steps)";
    std::snprintf(line, sizeof line, "%-9s %-10s %13.6f %13.6f %13.6f %12.6f %12.6f %12.6f %8lld %9.3f  %s\n",
                  t.engine.c_str(), t.body_names[b].c_str(), s.position.x(), s.position.y(),
                  s.position.z(), s.velocity.x(), s.velocity.y(), s.velocity.z(),
                  static_cast<long long>(t.recorded.back()), t.wall_seconds * 1e3, status.c_str());
    out << line;
  }
}

}  // namespace

int cmd_run(const std::vector<std::string>& argv, std::ostream& out, std::ostream&) {
  const Args args = parse_args(argv, {"--engine", "--dt", "--csv", "--json"}, {});
  if (args.positional.size() != 1) throw InputError("", 0, "run", "expects exactly one scene FILE");
  const Scene scene = load_scene(args.positional[0]);
  const Timestep dt = step_from_flag(args.value("--dt"), scene);
  std::vector<SelectedEngine> engines = select_engines(args.values("--engine"), scene);

  print_header(scene, dt, out);
  std::vector<Trajectory> runs;
  for (SelectedEngine& e : engines) {
    if (!e.engine) {
      out << e.name << "  skipped: " << e.skipped_because << "\n";
      continue;
    }
    runs.push_back(run_scene(*e.engine, scene, dt.seconds));
    print_run(runs.back(), out);
  }
  if (args.has("--csv")) write_file_atomic(args.value("--csv"), trajectories_to_csv(runs));
  if (args.has("--json")) write_file_atomic(args.value("--json"), trajectories_to_json(runs));
  return kExitOk;
}

}  // namespace dropcheck
