// Contact as an engine's own solver makes it, where the harness replays that solver
// (harness/core/contact_solver.hpp): the member a slide or a bounce on that engine is judged
// against, beside the ideal laws of contact_laws.hpp whose difference the replay explains.
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/contact_solver.hpp"
#include "harness/core/scene.hpp"
#include "harness/core/trajectory.hpp"
#include "harness/oracles/contact_laws.hpp"

namespace dropcheck {

// True for a solver the harness replays or re-solves (Box2D, Chipmunk, MuJoCo), or whose force law
// it steps (Simbody).
bool replayed(const ContactSolver& solver);

// The state of body `body` after steps 0..steps at step h under `solver`, as the engine reports it.
// `run`, the run being judged, steers MuJoCo's re-solve through collisions whose branch the last
// bits of the state decide (harness/oracles/mujoco_step.hpp MujocoSteer); the other replays are
// bit-exact and ignore it. Throws std::invalid_argument for an exact solver or a scene outside the
// replay's scope (harness/oracles/box2d_step.hpp, chipmunk_step.hpp, mujoco_step.hpp).
std::vector<BodyState> replayed_states(const Scene& scene, std::size_t body,
                                       const ContactSolver& solver, double h, std::int64_t steps,
                                       const Trajectory* run = nullptr);

// The path of `setup`'s slide, read as observed_slide_path reads a run.
SlidePath replayed_slide_path(const Scene& scene, const SlideSetup& setup,
                              const ContactSolver& solver, double h, std::int64_t steps,
                              const Trajectory* run = nullptr);

// The path of `setup`'s bounce, read as observed_path reads a run.
BouncePath replayed_bounce_path(const Scene& scene, const BounceSetup& setup,
                                const ContactSolver& solver, double h, std::int64_t steps,
                                const Trajectory* run = nullptr);

}  // namespace dropcheck
