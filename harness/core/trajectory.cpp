#include "harness/core/trajectory.hpp"

#include <algorithm>
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

std::string Trajectory::messages_text() const {
  if (messages.empty()) return {};
  std::vector<const Message*> by_count;
  for (const Message& m : messages) by_count.push_back(&m);
  std::stable_sort(by_count.begin(), by_count.end(),
                   [](const Message* a, const Message* b) { return a->count > b->count; });
  std::string text = engine + " printed ";
  const std::size_t shown = std::min<std::size_t>(3, by_count.size());
  for (std::size_t i = 0; i < shown; ++i) {
    const Message& m = *by_count[i];
    text += (i == 0           ? ""
             : i + 1 == shown ? " and "
                              : ", ") +
            ("'" + m.text + "' ") +
            (m.count == 1 ? std::string("once") : std::to_string(m.count) + " times");
  }
  std::int64_t more = other_lines;
  for (std::size_t i = shown; i < by_count.size(); ++i) more += by_count[i]->count;
  if (more > 0) text += " (and " + std::to_string(more) + " other lines)";
  return text;
}

}  // namespace dropcheck
