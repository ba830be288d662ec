// External forces, computed by the harness from the state at the start of each step and handed to
// every engine, so that all engines see the same force law.
#pragma once

#include <span>
#include <vector>

#include "harness/core/engine.hpp"

namespace dropcheck {

// Sum of the scene's forces on each body (N), indexed like Scene::bodies; zero for static bodies.
void compute_forces(const Scene& scene, std::span<const BodyState> states, std::span<Vec3> out);

// The force of one spring and its dashpot on a body in `state` (N).
Vec3 spring_force(const Spring& spring, const BodyState& state);

// The springs acting on each body, indexed like Scene::bodies (none for a static body); pointers
// into `scene`, valid while it lives.
std::vector<std::vector<const Spring*>> springs_by_body(const Scene& scene);

// The force on a body at a stage inside a step (a Runge-Kutta stage, harness/core/law.hpp): the
// step-start force `start_force` (what the harness computed and handed over) plus each spring's
// change from the body's step-start state `start` to the stage state `now`. Constant forces stay
// as given; a spring pulls from where the stage puts the body. Equal to compute_forces at `now`
// when start_force is compute_forces at `start`, up to rounding.
Vec3 stage_force(const Vec3& start_force, std::span<const Spring* const> springs,
                 const BodyState& start, const BodyState& now);

// Sum of the scene's constant torques on each body (N m, world frame), indexed like Scene::bodies;
// zero for static bodies.
void compute_torques(const Scene& scene, std::span<Vec3> out);

}  // namespace dropcheck
