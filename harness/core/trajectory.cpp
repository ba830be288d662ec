#include "harness/core/trajectory.hpp"

#include <cstdint>

namespace dropcheck {

const char* to_string(RunStatus status) {
  switch (status) {
    case RunStatus::ok:
      return "ok";
    case RunStatus::non_finite:
      return "non-finite state";
    case RunStatus::engine_error:
      return "engine error";
    case RunStatus::out_of_memory:
      return "out of memory";
    case RunStatus::crashed:
      return "crashed";
    case RunStatus::timed_out:
      return "timed out";
    case RunStatus::refused:
      return "refused";
  }
  return "?";
}

const char* status_key(RunStatus status) {
  switch (status) {
    case RunStatus::ok:
      return "ok";
    case RunStatus::non_finite:
      return "non-finite";
    case RunStatus::engine_error:
      return "engine-error";
    case RunStatus::out_of_memory:
      return "out-of-memory";
    case RunStatus::crashed:
      return "crashed";
    case RunStatus::timed_out:
      return "timed-out";
    case RunStatus::refused:
      return "refused";
  }
  return "?";
}

Trajectory unstarted_trajectory(const std::string& engine, const Scene& scene, double h) {
  Trajectory t;
  t.engine = engine;
  t.scene = scene.name;
  t.h = h;
  // A count beyond int64 (a refused run of 1e300 s) is clamped rather than rounded.
  t.steps = scene.duration / h < 9e18 ? step_count(scene, h) : INT64_MAX;
  for (const Body& b : scene.bodies) t.body_names.push_back(b.name);
  t.rotates = needs_rotation(scene);
  return t;
}

Trajectory failed_trajectory(const std::string& engine, const Scene& scene, double h,
                             RunStatus status, const std::string& failure, std::int64_t step) {
  Trajectory t = unstarted_trajectory(engine, scene, h);
  t.status = status;
  t.failure = failure;
  t.failed_step = step;
  return t;
}

}  // namespace dropcheck
