// A hand-written run for the contact verdict tests: every body of a scene at its start, at rest,
// except each body i moved by by[i] from step `from` on (every step recorded).
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/scene.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck::testing {

inline Trajectory displaced_run(const Scene& scene, std::int64_t steps, const std::vector<Vec3>& by,
                                std::int64_t from = 1) {
  Trajectory t;
  t.h = scene.timestep.seconds;
  t.steps = steps;
  for (const Body& b : scene.bodies) t.body_names.push_back(b.name);
  for (std::int64_t n = 0; n <= steps; ++n) {
    t.recorded.push_back(n);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Vec3 moved = i < by.size() && n >= from ? by[i] : Vec3::Zero();
      t.states.push_back({scene.bodies[i].position + moved, Vec3::Zero()});
    }
  }
  return t;
}

}  // namespace dropcheck::testing
