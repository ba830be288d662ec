#include "harness/oracles/replayed_contact.hpp"

#include <optional>
#include <stdexcept>
#include <vector>

#include "harness/core/box2d_world.hpp"
#include "harness/core/chipmunk_world.hpp"
#include "harness/core/mujoco_world.hpp"
#include "harness/oracles/box2d_step.hpp"
#include "harness/oracles/chipmunk_step.hpp"
#include "harness/oracles/mujoco_step.hpp"

namespace dropcheck {

bool replayed(const ContactSolver& solver) {
  return solver.kind != ContactSolverKind::exact;
}

namespace {

// The body's states under Box2D's replay.
std::vector<BodyState> box2d_states(const Scene& scene, std::size_t body,
                                    const ContactSolver& solver, double h, std::int64_t steps) {
  // The replay builds each body's mass from its fixture; the adapter sets the scene's moment over
  // it when the scene turns, and builds no fixture without contacts.
  if (!scene.world.contacts)
    throw std::invalid_argument("Box2D's replay needs contacts (the adapter builds no fixture)");
  if (needs_rotation(scene))
    throw std::invalid_argument(
        "Box2D's replay takes each fixture's own moment, and a turning scene sets the scene's");
  const Box2dWorld world = box2d_world(scene, h);
  const std::vector<Box2dState> states =
      box2d_replay(world.bodies, world.gx, world.gy, static_cast<float>(h),
                   {.velocity_iterations = solver.velocity_iterations,
                    .position_iterations = solver.position_iterations},
                   steps);
  std::vector<BodyState> out;
  for (std::size_t k = body; k < states.size(); k += world.bodies.size())
    out.push_back({Vec3(states[k].x, states[k].y, 0.0), Vec3(states[k].vx, states[k].vy, 0.0)});
  return out;
}

// The body's states under Chipmunk's replay.
std::vector<BodyState> chipmunk_states(const Scene& scene, std::size_t body,
                                       const ContactSolver& solver, double h, std::int64_t steps) {
  ChipmunkWorld world = chipmunk_world(scene);
  world.iterations = solver.velocity_iterations;
  const std::vector<ChipmunkState> states = chipmunk_replay(world, h, steps);
  std::vector<BodyState> out;
  for (std::size_t k = body; k < states.size(); k += world.bodies.size())
    out.push_back({Vec3(states[k].x, states[k].y, 0.0), Vec3(states[k].vx, states[k].vy, 0.0)});
  return out;
}

// The body's states under MuJoCo's re-solved step, steered through undecided collisions by `run`.
std::vector<BodyState> mujoco_states(const Scene& scene, std::size_t body, double h,
                                     std::int64_t steps, const Trajectory* run) {
  if (has_spheres(scene))
    throw std::invalid_argument(
        "MuJoCo's re-solve collides boxes only (the adapter builds no spheres)");
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (pushed(scene, i))
      throw std::invalid_argument("MuJoCo's re-solve takes no forces of the scene");
  const MujocoWorld world = mujoco_world(scene, h);
  std::optional<MujocoSteer> steer;
  if (run && run->keeps_every_step()) steer = MujocoSteer{run->states};
  const std::vector<MujocoState> states = mujoco_replay(world, steps, steer ? &*steer : nullptr);
  std::vector<BodyState> out{{scene.bodies[body].position, scene.bodies[body].velocity}};
  for (std::size_t k = body; k < states.size(); k += world.bodies.size())
    out.push_back({states[k].position, states[k].velocity});
  return out;
}

}  // namespace

std::vector<BodyState> replayed_states(const Scene& scene, std::size_t body,
                                       const ContactSolver& solver, double h, std::int64_t steps,
                                       const Trajectory* run) {
  switch (solver.kind) {
    case ContactSolverKind::box2d_2_4:
      return box2d_states(scene, body, solver, h, steps);
    case ContactSolverKind::chipmunk_7:
      return chipmunk_states(scene, body, solver, h, steps);
    case ContactSolverKind::mujoco_2_2:
      return mujoco_states(scene, body, h, steps, run);
    case ContactSolverKind::exact:
      break;
  }
  throw std::invalid_argument("replayed_states: the solver is not replayed");
}

SlidePath replayed_slide_path(const Scene& scene, const SlideSetup& setup,
                              const ContactSolver& solver, double h, std::int64_t steps,
                              const Trajectory* run) {
  return slide_path_of(replayed_states(scene, setup.body, solver, h, steps, run), setup);
}

BouncePath replayed_bounce_path(const Scene& scene, const BounceSetup& setup,
                                const ContactSolver& solver, double h, std::int64_t steps,
                                const Trajectory* run) {
  return bounce_path_of(replayed_states(scene, setup.body, solver, h, steps, run), setup);
}

}  // namespace dropcheck
