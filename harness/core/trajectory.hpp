// Trajectory: the sampled states of every body of one scene run on one engine at one step h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"

namespace dropcheck {

enum class RunStatus {
  ok,             // ran every step
  non_finite,     // a position or velocity became NaN or Inf, or an orientation stopped being a
                  // unit quaternion (recorded up to the step before)
  engine_error,   // the engine threw or reported an error
  out_of_memory,  // an allocation failed (std::bad_alloc); samples up to then are kept
  crashed,    // the engine's process died (signal or exit): an isolated run's (no samples) or an
              // external engine's (samples up to the step before)
  timed_out,  // the run exceeded the wall-clock limit: an isolated process is killed, an external
              // engine stopped after its step
  refused,    // not started: the run exceeds a limit (harness/run/run_limits.hpp)
};

struct Trajectory {
  std::string engine;
  std::string scene;
  double h = 0.0;
  std::int64_t steps = 0;               // steps the scene asks for
  std::vector<std::string> body_names;  // as in Scene::bodies
  std::vector<std::int64_t> recorded;   // step index of each sample; sample 0 is step 0
  // recorded.size() x body_names.size(), sample-major. Growing it with resize(n) or emplace_back()
  // leaves the new states unwritten (UnwrittenAllocator, engine.hpp): write them before any read.
  StateBuffer states;
  // For a scene that needs rotation (needs_rotation): the rotational state of every sample, laid
  // out like `states`. Empty, and `rotates` false, for every other scene.
  bool rotates = false;
  RotationBuffer rotations;
  // For a law's prediction that rotates: how much the law amplifies a small change of its start
  // (rotation_amplification, harness/oracles/own_rotation.hpp), the factor by which rounding may
  // grow; 1 otherwise.
  double amplification = 1.0;
  // ... and how many ulps of the largest |w| the engine's own rotational step may round to per step
  // beyond what any step rounds (RotationLaw::spatial_bias); 0 otherwise.
  double rotation_step_ulps = 0.0;
  RunStatus status = RunStatus::ok;
  std::string failure;             // what went wrong, for non-ok status
  std::int64_t failed_step = -1;   // first step that failed
  std::int64_t clamped_steps = 0;  // steps on which the engine clamped a speed
  std::int64_t first_clamped_step = -1;
  // Steps an error-controlled engine took of its own over the run (Engine::engine_steps), at least
  // one per step of h; 0 for a fixed-step engine, whose steps are the run's.
  std::int64_t engine_steps = 0;
  double wall_seconds = 0.0;  // stepping loop (forces, step, read, sampling), not load
  // The lines the engine wrote to stderr during an isolated run (harness/run/isolated_run.hpp),
  // each distinct one once with how often, in order of first appearance: at most kKeptMessages of
  // them, each cut to 300 bytes, controls escaped; the lines past those counted in `other_lines`.
  struct Message {
    std::string text;
    std::int64_t count = 0;
  };
  static constexpr std::size_t kKeptMessages = 16;
  std::vector<Message> messages;
  std::int64_t other_lines = 0;
  // "ode printed 'ODE message 3: LCP internal error, s <= 0' 352 times" (the three most frequent
  // lines, and how many more); "" when it printed nothing.
  std::string messages_text() const;

  std::size_t samples() const { return recorded.size(); }
  // Every step from 0 was kept (sample k is step k), as the contact laws' step-by-step checks need.
  bool keeps_every_step() const {
    return !recorded.empty() && recorded.back() + 1 == static_cast<std::int64_t>(recorded.size());
  }
  std::size_t bodies() const { return body_names.size(); }
  const BodyState& at(std::size_t sample, std::size_t body) const {
    return states[sample * bodies() + body];
  }
  // Body `body`'s state at every sample, in order.
  std::vector<BodyState> body_states(std::size_t body) const {
    std::vector<BodyState> out;
    out.reserve(samples());
    for (std::size_t k = 0; k < samples(); ++k) out.push_back(at(k, body));
    return out;
  }
  const RotationState& rotation_at(std::size_t sample, std::size_t body) const {
    return rotations[sample * bodies() + body];
  }
  double time(std::size_t sample) const { return static_cast<double>(recorded[sample]) * h; }
  const BodyState& final_state(std::size_t body) const { return at(samples() - 1, body); }
};

const char* to_string(RunStatus status);
// The same as one word for machine-read records: "ok", "non-finite", "engine-error",
// "out-of-memory", "crashed", "timed-out", "refused".
const char* status_key(RunStatus status);

// A trajectory with no samples yet: the names, h and step count of `scene` run on `engine`.
Trajectory unstarted_trajectory(const std::string& engine, const Scene& scene, double h);

// The same, ended before it began with `status` and `failure` (failed_step = `step`).
Trajectory failed_trajectory(const std::string& engine, const Scene& scene, double h,
                             RunStatus status, const std::string& failure, std::int64_t step = 0);

}  // namespace dropcheck
