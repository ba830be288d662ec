// Helpers shared by the adapter tests (tests/adapters/*_test.cpp): the shipped free-flight scenes,
// the worst departure of a run from its engine's law, and a drop-on-floor scene built in code.
#pragma once

#include <sstream>
#include <string>

#include "harness/core/scene_loader.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck::testing {

inline const char* const kFreeFlightScenes[] = {"seed_part3", "free_fall", "free_fall_drag", "wind",
                                                "throw_up"};

inline Scene scenario(const std::string& name) {
  return load_scene(std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/" + name + ".toml");
}

// The largest position difference between a run and its engine's law, and where it occurs.
struct WorstDx {
  double dx = 0.0;
  std::string where = "nowhere";
};

inline WorstDx worst_dx(const Trajectory& run, const Trajectory& law) {
  WorstDx w;
  for (std::size_t s = 0; s < run.samples(); ++s) {
    for (std::size_t b = 0; b < run.bodies(); ++b) {
      const double dx = (run.at(s, b).position - law.at(s, b).position).norm();
      if (dx <= w.dx) continue;
      std::ostringstream m;
      m.precision(17);
      m << "scene " << run.scene << ", engine " << run.engine << ", body " << run.body_names[b]
        << ", step " << run.recorded[s] << " (h = " << run.h << "): engine x = ("
        << run.at(s, b).position.transpose() << "), law x = (" << law.at(s, b).position.transpose()
        << "), |dx| = " << dx;
      w = {dx, m.str()};
    }
  }
  return w;
}

// A unit cube whose centre starts at 10 m above a static floor box whose top is at y = 0; no drag
// (the hardest landing: 13.6 m/s), as scenarios/drop_on_floor_undamped.toml.
inline Scene drop_on_floor() {
  Scene s;
  s.name = "drop_on_floor (in code)";
  s.duration = 5.0;
  s.world.gravity = Vec3(0.0, -9.8, 0.0);
  s.world.contacts = true;
  s.bodies.push_back({.name = "floor",
                      .half_extents = {10.0, 0.5, 10.0},
                      .position = {0.0, -0.5, 0.0},
                      .is_static = true});
  s.bodies.push_back({.name = "cube", .position = {0.0, 10.0, 0.0}});
  return s;
}

}  // namespace dropcheck::testing
