#include "harness/core/runner.hpp"

#include <chrono>
#include <new>
#include <optional>
#include <string>

#include "harness/core/forces.hpp"
#include "harness/core/isolated_run.hpp"
#include "harness/core/run_limits.hpp"

namespace dropcheck {
namespace {

bool finite(const BodyState& s) { return s.position.allFinite() && s.velocity.allFinite(); }

Trajectory empty_trajectory(const Engine& engine, const Scene& scene, double h) {
  Trajectory t;
  t.engine = engine.info().name;
  t.scene = scene.name;
  t.h = h;
  t.steps = step_count(scene, h);
  for (const Body& b : scene.bodies) t.body_names.push_back(b.name);
  return t;
}

// States first: if either allocation fails, samples() never counts a row that was not stored
// (recorded before states once let an out-of-memory run print unset rows, zeros, as final states).
void record(Trajectory& t, std::int64_t step, std::span<const BodyState> states) {
  t.states.insert(t.states.end(), states.begin(), states.end());
  t.recorded.push_back(step);
}

// Steps until the end or the first failure; returns normally in both cases.
// `n` is the step under way, for the caller to report an exception thrown by the engine.
void step_loop(Engine& engine, const Scene& scene, Trajectory& t, std::int64_t every,
               std::vector<BodyState>& states, std::int64_t& n) {
  std::vector<Vec3> forces(states.size());
  for (n = 1; n <= t.steps; ++n) {
    compute_forces(scene, states, forces);
    engine.set_forces(forces);
    engine.step();
    engine.read(states);
    if (engine.speed_clamped()) {
      if (t.clamped_steps++ == 0) t.first_clamped_step = n;
    }
    for (std::size_t i = 0; i < states.size(); ++i) {
      if (!finite(states[i])) {
        t.status = RunStatus::non_finite;
        t.failed_step = n;
        t.failure = "body '" + t.body_names[i] + "' has a NaN/Inf state at step " + std::to_string(n);
        return;
      }
    }
    if (n % every == 0 || n == t.steps) record(t, n, states);
  }
}

}  // namespace

Trajectory run_scene(Engine& engine, const Scene& scene, double h, const RunOptions& options) {
  if (std::optional<Trajectory> refused = refuse_run(engine.info(), scene, h, options)) return *refused;
  if (runs_isolated(options)) return run_isolated(engine, scene, h, options);
  return run_scene_in_process(engine, scene, h, options);
}

Trajectory run_scene_in_process(Engine& engine, const Scene& scene, double h,
                                const RunOptions& options) {
  Trajectory t = empty_trajectory(engine, scene, h);
  std::vector<BodyState> states(scene.bodies.size());
  std::int64_t n = 0;
  auto start = std::chrono::steady_clock::now();
  try {
    engine.load(scene, h);
    engine.read(states);
    record(t, 0, states);
    start = std::chrono::steady_clock::now();  // time the stepping loop, not the setup
    step_loop(engine, scene, t, options.record_every < 1 ? 1 : options.record_every, states, n);
  } catch (const std::bad_alloc&) {
    t.status = RunStatus::out_of_memory;
    t.failed_step = n;
    t.failure = "allocation failed at step " + std::to_string(n);
  } catch (const std::exception& e) {
    t.status = RunStatus::engine_error;
    t.failed_step = n;
    t.failure = e.what();
  }
  t.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}

}  // namespace dropcheck
