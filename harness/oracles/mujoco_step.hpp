// MuJoCo 2.2's step re-solved (harness/core/mujoco_world.hpp builds its parameters): the boxes of a
// world collided as mjc_BoxBox collides them, each contact's rows built as mj_instantiateContact,
// mj_diagApprox and mj_makeImpedance build them, and the step's convex problem solved exactly
// instead of iteratively; then mj_Euler. Read in MuJoCo's 2.2.2 tag (the Debian package's version):
// engine_collision_box.c, engine_collision_driver.c, engine_core_constraint.c, engine_forward.c,
// engine_util_spatial.c.
//
// The problem of one step (MuJoCo's "Computation" documentation): with the smooth acceleration
// a0 = M^-1 * (m*g + F - b*v - w x I*w), the step's acceleration is
//
//   a* = argmin_a  1/2 (a - a0)' M (a - a0) + sum_i s_i(J_i*a - aref_i)
//
// where each pyramid edge row i costs s_i(x) = 1/2 D_i x^2 when x < 0 and nothing otherwise (a
// contact pushes, never pulls). The cost is convex and piecewise quadratic: Newton's method with an
// exact line search reaches its minimum in finitely many steps, at the point where the active rows
// (x < 0) are those the last Newton step assumed. MuJoCo's own Newton solver stops when an
// iteration improves the cost by less than its tolerance (1e-8, scaled); tests measure how close
// that leaves it (tests/adapters/mujoco_test.cpp).
//
// Scope: boxes (mjc_BoxBox's face and edge branches) and spheres on boxes (mjc_SphereBox; no sphere
// on a sphere), either cone, solref in either format, a flat impedance, no forces or torques of
// the scene.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/mujoco_world.hpp"

namespace dropcheck {

// One dynamic body after a step, as MuJoCo's qpos and qvel hold it.
struct MujocoState {
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity_body = Vec3::Zero();
};

// What one step found: contacts and the active rows of its solution.
struct MujocoStepInfo {
  int contacts = 0;
  int active_rows = 0;
  int newton_iterations = 0;
  int undecided_pairs = 0;  // pairs whose collision branch the last bits of the state decide
};

// The run a replay follows where MuJoCo's collision is undecided: mjc_BoxBox takes a face or an
// edge branch by comparing two depths that, for a box resting flat on another, differ only in their
// last bits, and the branches report depths a factor 2 apart. No replay that is not bit-exact can
// decide those as the library did; the replay tries both and keeps the one that brings the step
// closer to the run's next position, as the turned-box contact law tries undecided corners both
// ways. `run` holds every body's state after steps 0, 1, ..., step-major (Trajectory::states).
struct MujocoSteer {
  std::span<const BodyState> run;
};

// The states of every body (static ones stay where they are) after steps 1..steps, step-major:
// entry (n - 1)*bodies + i is body i after step n; steered through undecided collisions by `steer`
// where given. Throws std::invalid_argument for a world outside the scope above.
std::vector<MujocoState> mujoco_replay(const MujocoWorld& world, std::int64_t steps,
                                       const MujocoSteer* steer = nullptr,
                                       std::vector<MujocoStepInfo>* info = nullptr);

}  // namespace dropcheck
