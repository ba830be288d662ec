// The harness loop against each engine's bare stepping loop, in ns per body-step, on N free cubes
// (gravity and damping, no contacts, no external forces) at h = 1/60:
//   bare/<engine>/<N>     the engine's own step call only (bare_step_loop, adapters/adapters.hpp)
//   harness/<engine>/<N>  run_scene: forces, set_forces, step, read, NaN check, a sample every step
//                         (what `dropcheck run` does)
//   sparse/<engine>/<N>   run_scene sampling only step 0 and the last step (record_every = steps):
//                         the loop without the memory traffic of keeping every state
//   bare-turning/..., harness-turning/..., sparse-turning/...: the same with every cube a tumbling
//   box (Gazebo's
//                         boxes: sides 0.1 x 0.9 x 0.4 m, w0 = (0.1, 0.1, -5) rad/s), so the
//                         harness also reads each body's rotation every step (engines that turn
//                         bodies in 3-D only)
// Loading is untimed in both (manual time = the stepping loop's own wall time). The counter
// ns_per_body_step is total loop time / (N * steps); scripts/bench.sh pairs the two into a ratio.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>

#include "adapters/adapters.hpp"
#include "harness/core/registry.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {
namespace {

constexpr double kH = 1.0 / 60.0;

// Steps per run: 600 (10 s) up to N = 1000, fewer above so that a run stays near 6e5 body-steps.
std::int64_t steps_for(int n) {
  return std::clamp<std::int64_t>(600000 / n, 60, 600);
}

// N unit cubes 2 m apart along x at y = 10 m, in the x-y plane (Box2D runs it), falling freely.
Scene free_cubes(int n) {
  Scene s;
  s.name = "free_cubes_" + std::to_string(n);
  s.duration = static_cast<double>(steps_for(n)) * kH;
  s.world.gravity = {0.0, -9.81, 0.0};
  s.world.damping_rate = 0.5;
  for (int i = 0; i < n; ++i) {
    Body b;
    b.name = "cube" + std::to_string(i);
    b.position = {2.0 * i, 10.0, 0.0};
    b.velocity = {0.0, 1.0, 0.0};
    s.bodies.push_back(b);
  }
  return s;
}

// The same cubes as tumbling boxes (a scene that needs rotation).
Scene turning_boxes(int n) {
  Scene s = free_cubes(n);
  s.name = "turning_boxes_" + std::to_string(n);
  for (Body& b : s.bodies) {
    b.mass = 10.0;
    b.half_extents = {0.05, 0.45, 0.2};
    b.angular_velocity = {0.1, 0.1, -5.0};
  }
  return s;
}

// Times `loop` (returns the seconds of one run) and reports ns per body-step.
template <typename Loop>
void measure(benchmark::State& state, int n, Loop&& loop) {
  double seconds = 0.0;
  std::int64_t body_steps = 0;
  for (auto _ : state) {
    const double s = loop();
    state.SetIterationTime(s);
    seconds += s;
    body_steps += n * steps_for(n);
  }
  state.counters["ns_per_body_step"] = 1e9 * seconds / static_cast<double>(body_steps);
  state.counters["steps"] = static_cast<double>(steps_for(n));
}

void bare(benchmark::State& state, const std::string& engine, int n, bool turning) {
  const Scene scene = turning ? turning_boxes(n) : free_cubes(n);
  measure(state, n, [&] { return bare_step_loop(engine, scene, kH); });
}

void harness(benchmark::State& state, const std::string& engine, int n, std::int64_t every,
             bool turning) {
  const Scene scene = turning ? turning_boxes(n) : free_cubes(n);
  measure(state, n, [&] {
    const std::unique_ptr<Engine> e = make_engine(engine);
    const Trajectory t = run_scene(*e, scene, kH, {.record_every = every});
    if (t.status != RunStatus::ok) state.SkipWithError(t.failure.c_str());
    return t.wall_seconds;
  });
}

// Registers bare, harness and sparse for every engine compiled in and every N, interleaved per N.
const bool registered = [] {
  for (const int n : {1, 100, 1000, 10000}) {
    for (const std::string& engine : available_engine_names()) {
      const std::string tail = engine + "/" + std::to_string(n);
      benchmark::RegisterBenchmark(("bare/" + tail).c_str(), bare, engine, n, false)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("harness/" + tail).c_str(), harness, engine, n, 1, false)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("sparse/" + tail).c_str(), harness, engine, n, steps_for(n),
                                   false)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
      if (n != 1000 || !make_engine(engine)->cannot_run(turning_boxes(1)).empty()) continue;
      benchmark::RegisterBenchmark(("bare-turning/" + tail).c_str(), bare, engine, n, true)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("harness-turning/" + tail).c_str(), harness, engine, n, 1, true)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("sparse-turning/" + tail).c_str(), harness, engine, n,
                                   steps_for(n), true)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
    }
  }
  return true;
}();

}  // namespace
}  // namespace dropcheck
