// External forces, computed by the harness from the state at the start of each step and handed to
// every engine, so that all engines see the same force law.
#pragma once

#include <span>
#include <vector>

#include "harness/core/engine.hpp"

namespace dropcheck {

// Sum of the scene's forces on each body (N), indexed like Scene::bodies; zero for static bodies.
void compute_forces(const Scene& scene, std::span<const BodyState> states, std::span<Vec3> out);

// Sum of the scene's constant torques on each body (N m, world frame), indexed like Scene::bodies;
// zero for static bodies.
void compute_torques(const Scene& scene, std::span<Vec3> out);

}  // namespace dropcheck
