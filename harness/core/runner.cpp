#include "harness/core/runner.hpp"

#include <bit>
#include <chrono>
#include <new>
#include <optional>
#include <string>
#include <variant>

#include "harness/core/forces.hpp"
#include "harness/core/isolated_run.hpp"
#include "harness/core/run_limits.hpp"

namespace dropcheck {
namespace {

bool finite(const BodyState& s) {
  return s.position.allFinite() && s.velocity.allFinite();
}

// True when every number of every state is finite, in one branch-free pass over the raw doubles
// (a BodyState is six contiguous doubles). A double is NaN or Inf exactly when its 11 exponent
// bits are all ones; adding one to the exponent field then carries into the sign bit, so the OR of
// (bits & exponent mask) + (one exponent unit) over all numbers has the sign bit set iff some
// number is not finite. Integer AND, ADD and OR vectorise; the per-body check runs only on failure.
// Eight independent accumulators (one body and a third per round): with a single one every OR
// waits for the previous one, and the pass cost half of ours's own step (perf, N = 1000).
bool all_finite(std::span<const BodyState> states) {
  static_assert(sizeof(BodyState) == 6 * sizeof(double));
  constexpr std::uint64_t kExponent = 0x7ff0000000000000u, kUnit = 0x0010000000000000u;
  constexpr std::size_t kLanes = 8;
  const auto* d = reinterpret_cast<const double*>(states.data());
  const std::size_t n = 6 * states.size();
  std::uint64_t any[kLanes] = {};
  std::size_t k = 0;
  for (; k + kLanes <= n; k += kLanes)
    for (std::size_t j = 0; j < kLanes; ++j)
      any[j] |= (std::bit_cast<std::uint64_t>(d[k + j]) & kExponent) + kUnit;
  for (; k < n; ++k) any[0] |= (std::bit_cast<std::uint64_t>(d[k]) & kExponent) + kUnit;
  std::uint64_t all = 0;
  for (const std::uint64_t a : any) all |= a;
  return (all >> 63) == 0;
}

bool has_springs(const Scene& scene) {
  for (const Force& f : scene.forces)
    if (std::holds_alternative<Spring>(f.law)) return true;
  return false;
}

// Samples a run of `steps` steps keeps: step 0, every `every`-th step and the last step.
std::size_t sample_count(std::int64_t steps, std::int64_t every) {
  return static_cast<std::size_t>(1 + steps / every + (steps % every != 0 ? 1 : 0));
}

Trajectory empty_trajectory(const Engine& engine, const Scene& scene, double h,
                            std::int64_t every) {
  Trajectory t;
  t.engine = engine.info().name;
  t.scene = scene.name;
  t.h = h;
  t.steps = step_count(scene, h);
  for (const Body& b : scene.bodies) t.body_names.push_back(b.name);
  // Sized once: the sample count is known before the first step.
  const std::size_t samples = sample_count(t.steps < 0 ? 0 : t.steps, every);
  t.recorded.reserve(samples);
  t.states.reserve(samples * scene.bodies.size());
  return t;
}

// Keeps the engine's current state as the next sample's states, at the end of t.states (the
// storage holds every sample, reserved once, so this never reallocates), and returns them. The
// engine constructs them there directly (Engine::read_append): no scratch copy, no zero-fill. The
// sample is counted (t.recorded) only once its states are checked; run_scene_in_process drops
// states that were not counted.
std::span<BodyState> read_sample(const Engine& engine, Trajectory& t, std::size_t bodies) {
  const std::size_t at = t.states.size();
  engine.read_append(bodies, t.states);
  if (t.states.size() != at + bodies)
    throw EngineError("read_append gave " + std::to_string(t.states.size() - at) + " states for " +
                      std::to_string(bodies) + " bodies");
  return std::span(t.states).subspan(at, bodies);
}

// Names the first body with a NaN/Inf state and ends the run there.
void fail_non_finite(Trajectory& t, std::span<const BodyState> states, std::int64_t n) {
  std::size_t i = 0;
  while (i + 1 < states.size() && finite(states[i])) ++i;
  t.status = RunStatus::non_finite;
  t.failed_step = n;
  t.failure = "body '" + t.body_names[i] + "' has a NaN/Inf state at step " + std::to_string(n);
}

// True when every component of every force is +0.0 (all bits zero).
bool all_zero(std::span<const Vec3> forces) {
  std::uint64_t any = 0;
  for (const Vec3& f : forces)
    for (int k = 0; k < 3; ++k) any |= std::bit_cast<std::uint64_t>(f[k]);
  return any == 0;
}

// Steps until the end or the first failure; returns normally in both cases. `current` holds the
// state at step 0 and then each step's state: read into the trajectory's next slot on a kept step,
// into `scratch` (which stays in cache) otherwise. `n` is the step under way, for the caller to
// report an exception thrown by the engine.
void step_loop(Engine& engine, const Scene& scene, Trajectory& t, std::int64_t every,
               std::span<BodyState> current, std::int64_t& n) {
  std::vector<BodyState> scratch(current.size());
  std::vector<Vec3> forces(current.size());
  // Constant forces do not depend on the state: summed once, in the same order as every step would.
  const bool state_dependent = has_springs(scene);
  compute_forces(scene, current, forces);
  // Constant forces that are all +0.0 (free flight, contacts): handed over on step 1 only. An
  // engine applies a force to the next step only (Engine::set_forces), so it holds zero applied
  // force after each step, and handing it the same zeros again would change nothing but cost a
  // pass over every body per step (an engine that keeps the last forces keeps these zeros).
  const bool no_forces = !state_dependent && all_zero(forces);
  for (n = 1; n <= t.steps; ++n) {
    if (state_dependent) compute_forces(scene, current, forces);
    if (n == 1 || !no_forces) engine.set_forces(forces);
    engine.step();
    const bool keep = n % every == 0 || n == t.steps;
    if (keep) {
      current = read_sample(engine, t, scratch.size());
    } else {
      current = scratch;
      engine.read(current);
    }
    if (engine.speed_clamped()) {
      if (t.clamped_steps++ == 0) t.first_clamped_step = n;
    }
    if (!all_finite(current)) return fail_non_finite(t, current, n);
    if (keep) t.recorded.push_back(n);
  }
}

}  // namespace

Trajectory run_scene(Engine& engine, const Scene& scene, double h, const RunOptions& options) {
  if (std::optional<Trajectory> refused = refuse_run(engine.info(), scene, h, options))
    return *refused;
  if (runs_isolated(options)) return run_isolated(engine, scene, h, options);
  return run_scene_in_process(engine, scene, h, options);
}

Trajectory run_scene_in_process(Engine& engine, const Scene& scene, double h,
                                const RunOptions& options) {
  const std::int64_t every = options.record_every < 1 ? 1 : options.record_every;
  Trajectory t = empty_trajectory(engine, scene, h, every);
  std::int64_t n = 0;
  auto start = std::chrono::steady_clock::now();
  try {
    engine.load(scene, h);
    const std::span<BodyState> initial = read_sample(engine, t, scene.bodies.size());
    t.recorded.push_back(0);
    start = std::chrono::steady_clock::now();  // time the stepping loop, not the setup
    step_loop(engine, scene, t, every, initial, n);
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
  t.states.resize(t.samples() * t.bodies());  // drops the slot of a step that failed
  return t;
}

}  // namespace dropcheck
