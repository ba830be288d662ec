#include "harness/run/runner.hpp"

#include <bit>
#include <chrono>
#include <cmath>
#include <new>
#include <optional>
#include <string>
#include <variant>

#include "harness/core/engine_writer.hpp"
#include "harness/core/forces.hpp"
#include "harness/run/isolated_run.hpp"
#include "harness/run/run_limits.hpp"

namespace dropcheck {
namespace {

bool finite_states(const BodyState& s) {
  return s.position.allFinite() && s.velocity.allFinite();
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
  Trajectory t = unstarted_trajectory(engine.info().name, scene, h);
  // Sized once: the sample count is known before the first step.
  const std::size_t samples = sample_count(t.steps < 0 ? 0 : t.steps, every);
  t.recorded.reserve(samples);
  t.states.reserve(samples * scene.bodies.size());
  if (t.rotates) t.rotations.reserve(samples * scene.bodies.size());
  return t;
}

// Appends the engine's current state for `bodies` bodies to `buffer` (Engine::read_append: written
// once, checked in the same pass) and returns them; `finite` says whether every number is. For
// t.states (storage for every sample, reserved once: this never reallocates) the sample is counted
// (t.recorded) only once checked; run_scene_in_process drops states that were not counted.
std::span<BodyState> read_states(const Engine& engine, StateBuffer& buffer, std::size_t bodies,
                                 StateUse use, bool& finite) {
  const std::size_t at = buffer.size();
  finite = engine.read_append(bodies, buffer, use);
  if (buffer.size() != at + bodies)
    throw EngineError("read_append gave " + std::to_string(buffer.size() - at) + " states for " +
                      std::to_string(bodies) + " bodies");
  return std::span(buffer).subspan(at, bodies);
}

bool finite_states(const RotationState& r) {
  return all_finite(std::span(&r, 1));
}

// Appends the engine's rotational state for `bodies` bodies to `buffer` (Engine::
// read_rotation_append: written once, checked in the same pass) and returns them; `sound` says
// whether every number is finite and every orientation a unit quaternion (rotations_sound).
std::span<const RotationState> read_rotations(const Engine& engine, RotationBuffer& buffer,
                                              std::size_t bodies, StateUse use, bool& sound) {
  const std::size_t at = buffer.size();
  sound = engine.read_rotation_append(bodies, buffer, use);
  if (buffer.size() != at + bodies)
    throw EngineError("read_rotation_append gave " + std::to_string(buffer.size() - at) +
                      " rotations for " + std::to_string(bodies) + " bodies");
  return std::span<const RotationState>(buffer).subspan(at, bodies);
}

// The first body whose orientation is not a unit quaternion (beyond kUnitSlack), or -1.
std::ptrdiff_t non_unit(std::span<const RotationState> rotations) {
  for (std::size_t i = 0; i < rotations.size(); ++i)
    if (!rotations_sound(rotations.subspan(i, 1))) return static_cast<std::ptrdiff_t>(i);
  return -1;
}

// Ends the run at step n: body `i`'s orientation is not a unit quaternion. Counted with the
// non-finite states: a law that overflows normalises its quaternion to zero (|q|^2 = inf), and an
// engine that answers no rotation has left the states a run can judge.
void fail_non_unit(Trajectory& t, std::span<const RotationState> rotations, std::size_t i,
                   std::int64_t n) {
  t.status = RunStatus::non_finite;
  t.failed_step = n;
  t.failure = "body '" + t.body_names[i] +
              "' has an orientation that is not a unit quaternion (norm " +
              std::to_string(rotations[i].orientation.norm()) + ") at step " + std::to_string(n);
}

// Names the first body with a NaN/Inf state (position, velocity or, when the run rotates,
// orientation and angular velocity) and ends the run there.
void fail_non_finite(Trajectory& t, std::span<const BodyState> states,
                     std::span<const RotationState> rotations, std::int64_t n) {
  std::size_t i = 0;
  while (i + 1 < states.size() && finite_states(states[i]) &&
         (rotations.empty() || finite_states(rotations[i])))
    ++i;
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

// How kept records (states, or rotational states) are written. Streamed past the cache
// (StateUse::kept) only when nothing reads them during the run (no springs: the next step's forces
// read the state; rotations are never read) and both the run and a step are large: there normal
// stores would spill out of the caches anyway, reading each line in before writing it. Measured
// (bench/loop_bench.cpp, every step kept, min of 6, load ~2), ns per body-step: N = 1000 (29 MB
// per run) ours 8.93 normal vs 5.93 streamed, ours-f64 10.11 vs 6.87; N = 100 (2.9 MB) and N = 1,
// streaming everything cost 0-0.5 ns more than normal stores.
template <typename Buffer>
StateUse kept_use(const Buffer& kept, std::size_t bodies, bool read_during_run) {
  constexpr std::size_t kMinStep = 4 << 10, kMinRun = 16 << 20;  // bytes
  using Record = typename Buffer::value_type;
  const std::size_t step_bytes = bodies * sizeof(Record);
  const bool large = step_bytes >= kMinStep && kept.capacity() * sizeof(Record) >= kMinRun;
  return large && !read_during_run ? StateUse::kept : StateUse::next_step;
}

// Ends the run at step n, where a state is not finite or an orientation not a unit quaternion.
void fail_at(Trajectory& t, std::span<const BodyState> states,
             std::span<const RotationState> rotations, std::int64_t n) {
  if (!all_finite(states) || !all_finite(rotations))
    return fail_non_finite(t, states, rotations, n);
  if (const std::ptrdiff_t i = non_unit(rotations); i >= 0)
    fail_non_unit(t, rotations, static_cast<std::size_t>(i), n);
}

// Steps until the end or the first failure; returns normally in both cases. `current` holds the
// state at step 0 and then each step's state: read into the trajectory's next slots on a kept
// step, into `scratch` (which stays in cache) otherwise; kept states as kept_states_use says. `n`
// is the step under way, for the caller to report an exception thrown by the engine.
void step_loop(Engine& engine, const Scene& scene, Trajectory& t, std::int64_t every,
               std::span<BodyState> current, std::int64_t& n) {
  const std::size_t bodies = current.size();
  StateBuffer scratch;
  scratch.reserve(bodies);
  RotationBuffer rotation_scratch;
  rotation_scratch.reserve(t.rotates ? bodies : 0);
  std::vector<Vec3> forces(bodies);
  // Constant forces do not depend on the state: summed once, in the same order as every step would.
  const bool state_dependent = has_springs(scene);
  const StateUse kept_states = kept_use(t.states, bodies, state_dependent);
  const StateUse kept_turns = kept_use(t.rotations, bodies, false);
  compute_forces(scene, current, forces);
  // Constant forces that are all +0.0 (free flight, contacts): handed over on step 1 only. An
  // engine applies a force to the next step only (Engine::set_forces), so it holds zero applied
  // force after each step, and handing it the same zeros again would change nothing but cost a
  // pass over every body per step (an engine that keeps the last forces keeps these zeros).
  const bool no_forces = !state_dependent && all_zero(forces);
  // Torques are constant (Scene::torques): summed once, handed over every step they are not zero.
  std::vector<Vec3> torques;
  if (t.rotates) {
    torques.resize(bodies);
    compute_torques(scene, torques);
  }
  const bool twisted = !all_zero(torques);
  for (n = 1; n <= t.steps; ++n) {
    if (state_dependent) compute_forces(scene, current, forces);
    if (n == 1 || !no_forces) engine.set_forces(forces);
    if (twisted) engine.set_torques(torques);
    engine.step();
    const bool keep = n % every == 0 || n == t.steps;
    bool finite = false;
    if (keep) {
      current = read_states(engine, t.states, bodies, kept_states, finite);
    } else {
      scratch.clear();
      current = read_states(engine, scratch, bodies, StateUse::next_step, finite);
    }
    std::span<const RotationState> turned;
    bool sound = true;
    if (t.rotates) {
      if (keep) {
        turned = read_rotations(engine, t.rotations, bodies, kept_turns, sound);
      } else {
        rotation_scratch.clear();
        turned = read_rotations(engine, rotation_scratch, bodies, StateUse::next_step, sound);
      }
    }
    if (engine.speed_clamped()) {
      if (t.clamped_steps++ == 0) t.first_clamped_step = n;
    }
    if (!finite || !sound) return fail_at(t, current, turned, n);
    if (keep) t.recorded.push_back(n);
  }
}

}  // namespace

Trajectory run_scene(Engine& engine, const Scene& scene, double h, const RunOptions& options) {
  if (std::optional<Trajectory> refused = refuse_run(engine.info(), scene, h, options))
    return *refused;
  if (engine.info().own_process) return run_own_process(engine, scene, h, options);
  if (runs_isolated(options)) return run_isolated(engine, scene, h, options);
  // A limit in this process: checked after every step (run_own_process's deadline).
  if (options.time_limit_seconds > 0) return run_own_process(engine, scene, h, options);
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
    bool finite = false;  // the scene's own numbers, finite by validation (scene_loader.hpp)
    const std::span<BodyState> initial =
        read_states(engine, t.states, scene.bodies.size(), StateUse::next_step, finite);
    if (t.rotates) {
      bool sound = false;
      const std::span<const RotationState> start =
          read_rotations(engine, t.rotations, scene.bodies.size(), StateUse::next_step, sound);
      if (const std::ptrdiff_t i = non_unit(start); i >= 0)
        throw EngineError("body '" + t.body_names[static_cast<std::size_t>(i)] +
                          "' starts with an orientation that is not a unit quaternion");
    }
    t.recorded.push_back(0);
    start = std::chrono::steady_clock::now();  // time the stepping loop, not the setup
    step_loop(engine, scene, t, every, initial, n);
  } catch (const EngineDied& e) {
    t.status = RunStatus::crashed;
    t.failed_step = n;
    t.failure = e.what();
  } catch (const RunTimeLimitExceeded& e) {
    t.status = RunStatus::timed_out;
    t.failed_step = n;
    t.failure = std::string(e.what()) + "; stopped at step " + std::to_string(n);
  } catch (const std::bad_alloc&) {
    t.status = RunStatus::out_of_memory;
    t.failed_step = n;
    t.failure = "allocation failed at step " + std::to_string(n);
  } catch (const std::exception& e) {
    t.status = RunStatus::engine_error;
    t.failed_step = n;
    t.failure = e.what();
  }
  end_streamed_writes();  // kept states streamed by the engine: ordered before what follows
  t.engine_steps = engine.engine_steps();
  t.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  t.states.resize(t.samples() * t.bodies());  // drops the slot of a step that failed
  if (t.rotates) t.rotations.resize(t.samples() * t.bodies());
  return t;
}

}  // namespace dropcheck
