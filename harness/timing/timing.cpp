#include "harness/timing/timing.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <map>
#include <variant>

#include "harness/core/engine_listing.hpp"
#include "harness/run/runner.hpp"
#include "harness/timing/calibration.hpp"

namespace dropcheck {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The full harness loop (forces, step, read, NaN check, a sample every step) as run_scene does it,
// in this process: a child process would leave this thread idle while the engine runs, so every
// run would look disturbed (wall time far beyond this thread's CPU time) and be measured twice.
// Only engines whose isolated run at this step finished are timed (harness/study/evaluate.cpp).
// `repeats` runs back to back, each loaded afresh; the sum of their stepping loops' wall times.
double time_full(Engine& engine, const Scene& scene, double h, int repeats) {
  RunOptions in_process;
  in_process.isolation = Isolation::in_process;
  double seconds = 0.0;
  for (int r = 0; r < repeats; ++r) seconds += run_scene(engine, scene, h, in_process).wall_seconds;
  return seconds;
}

// The engine alone: load, then step() only. An engine that throws ends the loop (its failure is
// the run's business, recorded by run_scene; here it only must not abort the timing).
double time_bare_once(Engine& engine, const Scene& scene, double h) {
  try {
    engine.load(scene, h);
  } catch (const std::exception&) {
    return 0.0;
  }
  const std::int64_t steps = step_count(scene, h);
  const auto start = Clock::now();
  try {
    for (std::int64_t n = 0; n < steps; ++n) engine.step();
  } catch (const std::exception&) {
  }
  return seconds_since(start);
}

// `repeats` bare loops back to back, each loaded afresh (untimed); the sum of the loops' times.
double time_bare(Engine& engine, const Scene& scene, double h, int repeats) {
  double seconds = 0.0;
  for (int r = 0; r < repeats; ++r) seconds += time_bare_once(engine, scene, h);
  return seconds;
}

// Body-steps of one copy of `scene` at h: dynamic bodies (at least 1) times steps (at least 1).
double body_steps_per_copy(const Scene& scene, double h) {
  double dynamic = 0.0;
  for (const Body& b : scene.bodies) dynamic += b.is_static ? 0.0 : 1.0;
  return std::max(dynamic, 1.0) *
         static_cast<double>(std::max<std::int64_t>(step_count(scene, h), 1));
}

// CPU time this thread has used (s): it does not advance while another process has the core.
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Runs `timed` (load + loop; returns the loop's wall seconds) until this thread ran it
// undisturbed: the call's wall time exceeds its CPU time by at most 5 % of the loop's time plus
// 100 us (on this 2-core VM an undisturbed call shows 40 to 150 us of such excess: interrupts,
// the hypervisor). A sample during which another process took the core is measured again, at
// most `retries` times; then the least disturbed one is kept. Counts the repeats in `disturbed`.
template <typename F>
double undisturbed(F&& timed, int retries, int& disturbed) {
  double best = 0.0, best_excess = 0.0;
  for (int attempt = 0; attempt <= retries; ++attempt) {
    const auto wall0 = Clock::now();
    const double cpu0 = thread_cpu_seconds();
    const double loop = timed();
    const double excess = seconds_since(wall0) - (thread_cpu_seconds() - cpu0);
    if (attempt == 0 || excess < best_excess) best = loop, best_excess = excess;
    if (excess <= 0.05 * loop + 100e-6) break;
    ++disturbed;
  }
  return best;
}

// Width of the scene along x (m), from the lowest to the highest box face of any body.
double x_extent(const Scene& scene) {
  double lo = 0.0, hi = 0.0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Body& b = scene.bodies[i];
    const double a = b.position.x() - b.half_extents.x(), c = b.position.x() + b.half_extents.x();
    lo = i ? std::min(lo, a) : a;
    hi = i ? std::max(hi, c) : c;
  }
  return hi - lo;
}

}  // namespace

Scene replicate(const Scene& scene, int copies) {
  Scene out = scene;
  const Vec3 step(x_extent(scene) + 10.0, 0.0, 0.0);
  for (int c = 1; c < copies; ++c) {
    const Vec3 offset = step * c;
    const std::size_t first = out.bodies.size();
    for (Body b : scene.bodies) {
      b.name += '#';  // two appends: "#" + to_string trips a GCC 12 -Wstringop-overflow false alarm
      b.name += std::to_string(c);
      b.position += offset;
      out.bodies.push_back(b);
    }
    for (Force f : scene.forces) {
      for (std::size_t& i : f.bodies) i += first;
      if (auto* s = std::get_if<Spring>(&f.law)) s->anchor += offset;
      out.forces.push_back(f);
    }
    for (Torque t : scene.torques) {  // a torque has no anchor: the same on every copy
      for (std::size_t& i : t.bodies) i += first;
      out.torques.push_back(t);
    }
  }
  return out;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double at = q * static_cast<double>(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(at);
  if (i + 1 >= v.size()) return v.back();
  return v[i] + (at - static_cast<double>(i)) * (v[i + 1] - v[i]);
}

const char* to_string(Statistic s) {
  switch (s) {
    case Statistic::min:
      return "minimum";
    case Statistic::q25:
      return "lower quartile";
    case Statistic::median:
      return "median";
  }
  return "?";
}

double statistic(const std::vector<double>& samples, Statistic s) {
  switch (s) {
    case Statistic::min:
      return quantile(samples, 0.0);
    case Statistic::q25:
      return quantile(samples, 0.25);
    case Statistic::median:
      return quantile(samples, 0.5);
  }
  return 0.0;
}

double ratio_of(const std::vector<double>& samples, const std::vector<double>& calibration,
                Statistic s) {
  const double reference = statistic(calibration, s);
  return reference > 0.0 ? statistic(samples, s) / reference : 0.0;
}

double Timing::ratio(Statistic s) const {
  return ratio_of(full, calibration, s);
}

double Timing::overhead() const {
  const double bare_median = bare_of(Statistic::median);
  return bare_median > 0 ? of(Statistic::median) / bare_median - 1 : 0;
}

int replicas_for(const Scene& scene, double h, const std::string& engine,
                 const TimingOptions& options) {
  const double per_copy =
      body_steps_per_copy(scene, h) * 1e-9 * nominal_ns_per_body_step(engine, scene.world.contacts);
  int copies = 1;
  while (copies < options.max_replicas && copies * per_copy < options.min_run_seconds) copies *= 2;
  return std::min(copies, std::max(options.max_replicas, 1));
}

double nominal_ns_per_body_step(const std::string& engine, bool contacts) {
  // Each engine's figure is declared with it (adapters/engines.txt, where it was measured); an
  // engine not in the list (an external one) is planned as a slow one.
  const EngineListing* listing = find_engine_listing(engine);
  if (!listing) return 1000.0;
  return contacts ? listing->nominal_contact_ns_per_body_step : listing->nominal_ns_per_body_step;
}

int repeats_for(const Scene& scene, double h, const std::string& engine, int replicas,
                const TimingOptions& options) {
  const double sample = body_steps_per_copy(scene, h) * std::max(replicas, 1) * 1e-9 *
                        nominal_ns_per_body_step(engine, scene.world.contacts);
  int repeats = 1;
  while (repeats < options.max_repeats && repeats * sample < options.min_sample_seconds)
    repeats *= 2;
  return std::min(repeats, std::max(options.max_repeats, 1));
}

TimingPlan timing_plan(const Scene& scene, double h, const std::string& engine,
                       const TimingOptions& options) {
  TimingPlan p;
  p.replicas = replicas_for(scene, h, engine, options);
  p.repeats = repeats_for(scene, h, engine, p.replicas, options);
  const double sample = body_steps_per_copy(scene, h) * p.replicas * p.repeats * 1e-9 *
                        nominal_ns_per_body_step(engine, scene.world.contacts);
  p.warmed = sample <= options.long_sample_seconds;
  p.samples = p.warmed ? options.samples : std::min(options.long_samples, options.samples);
  return p;
}

namespace {

// One cell of the timing: `engines` on `scene` (not owned) at step h.
struct TimingCell {
  const Scene* scene = nullptr;
  double h = 0.0;
  const std::vector<std::pair<std::string, EngineFactory>>& engines;
};

// One cell while it is being timed: each engine's plan, the replicated scenes (one per distinct
// number of copies), and the samples.
struct CellRun {
  std::vector<TimingPlan> plans;
  std::map<int, Scene> copies;
  const Scene& copies_of(std::size_t e) const { return copies.at(plans[e].replicas); }
  std::vector<std::vector<double>> full, bare;
  std::vector<double> calibration;  // one per timed round
  std::vector<int> disturbed;
};

CellRun start_cell(const TimingCell& cell, const TimingOptions& options) {
  CellRun run;
  const std::size_t ne = cell.engines.size();
  run.full.resize(ne);
  run.bare.resize(ne);
  run.disturbed.assign(ne, 0);
  for (std::size_t e = 0; e < ne; ++e) {
    const TimingPlan& p =
        run.plans.emplace_back(timing_plan(*cell.scene, cell.h, cell.engines[e].first, options));
    if (!run.copies.count(p.replicas))
      run.copies.emplace(p.replicas, replicate(*cell.scene, p.replicas));
  }
  return run;
}

// One round of one cell: every engine once, forward in even rounds and backward in odd ones. An
// untimed bare loop first brings the engine's code and data back in cache after whatever ran
// before, so that no figure depends on which engine or cell ran before it.
void time_round(const TimingCell& cell, CellRun& run, int round, const TimingOptions& options) {
  const std::size_t ne = cell.engines.size();
  int calibration_disturbed = 0;
  const double c =
      undisturbed([] { return time_calibration(); }, options.retries, calibration_disturbed);
  if (round >= 0) run.calibration.push_back(c);
  for (std::size_t k = 0; k < ne; ++k) {
    const std::size_t e = (round % 2 == 0) ? k : ne - 1 - k;
    const TimingPlan& plan = run.plans[e];
    if (round >= plan.samples || (round < 0 && !plan.warmed)) continue;
    std::unique_ptr<Engine> engine = cell.engines[e].second();
    const Scene& copies = run.copies_of(e);
    if (plan.warmed) time_bare(*engine, copies, cell.h, 1);
    const int n = plan.repeats;
    int& d = run.disturbed[e];
    const double f =
        undisturbed([&] { return time_full(*engine, copies, cell.h, n); }, options.retries, d);
    const double b =
        undisturbed([&] { return time_bare(*engine, copies, cell.h, n); }, options.retries, d);
    if (round >= 0) run.full[e].push_back(f), run.bare[e].push_back(b);
  }
}

// Engine e's samples, per simulated second of one copy, and the cell's calibration samples.
Timing summarise(const TimingCell& cell, const CellRun& run, std::size_t e) {
  Timing t;
  t.engine = cell.engines[e].first;
  t.h = cell.h;
  t.replicas = run.plans[e].replicas;
  t.repeats = run.plans[e].repeats;
  t.disturbed = run.disturbed[e];
  const double per = 1.0 / (cell.scene->duration * t.replicas * t.repeats);
  for (double s : run.full[e]) t.full.push_back(s * per);
  for (double s : run.bare[e]) t.bare.push_back(s * per);
  // The calibration loops of the rounds it ran (the first ones).
  t.calibration.assign(run.calibration.begin(),
                       run.calibration.begin() + static_cast<std::ptrdiff_t>(t.full.size()));
  return t;
}

}  // namespace

std::vector<Timing> time_engines(const std::vector<std::pair<std::string, EngineFactory>>& engines,
                                 const Scene& scene, double h, const TimingOptions& options) {
  const TimingCell cell{&scene, h, engines};
  CellRun run = start_cell(cell, options);
  for (int r = -options.warmups; r < options.samples; ++r) time_round(cell, run, r, options);
  std::vector<Timing> out;
  for (std::size_t e = 0; e < engines.size(); ++e) out.push_back(summarise(cell, run, e));
  return out;
}

}  // namespace dropcheck
