// The harness loop against each engine's bare stepping loop, in ns per body-step, on N free cubes
// (gravity and damping, no contacts, no external forces) at h = 1/60:
//   bare/<engine>/<N>     the engine's own step call only (bare_step_loop, adapters/adapters.hpp)
//   harness/<engine>/<N>  run_scene: forces, set_forces, step, read, NaN check, a sample every step
//                         (what `dropcheck run` does)
//   sparse/<engine>/<N>   run_scene sampling only step 0 and the last step (record_every = steps):
//                         the loop without the memory traffic of keeping every state
// Loading is untimed in both (manual time = the stepping loop's own wall time). The counter
// ns_per_body_step is total loop time / (N * steps); scripts/bench.sh pairs the two into a ratio.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>

#include "adapters/adapters.hpp"
#include "harness/core/registry.hpp"
#include "harness/core/runner.hpp"

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

void bare(benchmark::State& state, const std::string& engine, int n) {
  const Scene scene = free_cubes(n);
  measure(state, n, [&] { return bare_step_loop(engine, scene, kH); });
}

void harness(benchmark::State& state, const std::string& engine, int n, std::int64_t every) {
  const Scene scene = free_cubes(n);
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
      benchmark::RegisterBenchmark(("bare/" + tail).c_str(), bare, engine, n)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("harness/" + tail).c_str(), harness, engine, n, 1)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("sparse/" + tail).c_str(), harness, engine, n, steps_for(n))
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond);
    }
  }
  return true;
}();

}  // namespace
}  // namespace dropcheck
