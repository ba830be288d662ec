#include "harness/oracles/replayed_contact.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/core/box2d_world.hpp"
#include "harness/core/chipmunk_world.hpp"
#include "harness/core/mujoco_world.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/simbody_contact.hpp"
#include "harness/oracles/box2d_step.hpp"
#include "harness/oracles/chipmunk_step.hpp"
#include "harness/oracles/mujoco_step.hpp"
#include "harness/oracles/simbody_brick_step.hpp"

namespace dropcheck {

bool replayed(const ContactSolver& solver) {
  return solver.kind == ContactSolverKind::box2d_2_4 ||
         solver.kind == ContactSolverKind::chipmunk_7 ||
         solver.kind == ContactSolverKind::mujoco_2_2 ||
         solver.kind == ContactSolverKind::hunt_crossley;
}

namespace {

// Box2D and Chipmunk replay one dynamic body on one static body, and Simbody's force law pushes one
// dynamic body from its floor (Simbody 3.7 tracks no brick-brick contact). A scene of several
// dynamic bodies
// that never touch one another is several such problems: Box2D solves each island of touching
// bodies alone and a static body joins no island (b2World::Solve), and Chipmunk's arbiters each
// change the velocity of their one dynamic body only (a static body's inverse mass is 0), with no
// early exit across them. So body `body` moves as it would with the static bodies alone, in the
// same order, as long as no other dynamic body comes near it; replay_alone checks that.
struct Alone {
  Scene scene;
  std::size_t body = 0;  // its index in `scene`
};

Alone alone(const Scene& scene, std::size_t body) {
  Alone out{scene, 0};
  out.scene.bodies.clear();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    if (i == body || scene.bodies[i].is_static) {
      if (i == body) out.body = out.scene.bodies.size();
      out.scene.bodies.push_back(scene.bodies[i]);
    }
  return out;
}

// The radius of the sphere about the body's centre that holds its shape.
double reach(const Body& b) {
  return b.shape == Shape::sphere ? b.radius : b.half_extents.norm();
}

// How close two bodies' spheres may come while neither engine can see them touch: Box2D's contact
// points need the shapes within their skins (2 x 0.01 m), Chipmunk's an overlap (its collision
// slop here 0.005 m, harness/core/chipmunk_world.hpp); 0.2 m stays well outside both.
constexpr double kApart = 0.2;

using ReplayOne = std::vector<BodyState> (*)(const Scene&, std::size_t, const ContactSolver&,
                                             double, std::int64_t);

// `replay` of body `body` of `scene` with the static bodies alone, after checking that every other
// dynamic body, replayed alone in the same way, stays kApart from it at every step. `in_scene`:
// each body replayed in the whole scene instead (Simbody's force law takes its stiffness from every
// body of the scene, and pushes each from its floor alone).
std::vector<BodyState> replay_alone(ReplayOne replay, const Scene& scene, std::size_t body,
                                    const ContactSolver& solver, double h, std::int64_t steps,
                                    bool in_scene = false) {
  const auto replay_one = [&](std::size_t i) {
    if (in_scene) return replay(scene, i, solver, h, steps);
    const Alone own = alone(scene, i);
    return replay(own.scene, own.body, solver, h, steps);
  };
  std::vector<BodyState> states = replay_one(body);
  for (std::size_t j = 0; j < scene.bodies.size(); ++j) {
    if (j == body || scene.bodies[j].is_static) continue;
    const std::vector<BodyState> theirs = replay_one(j);
    const double apart = reach(scene.bodies[body]) + reach(scene.bodies[j]) + kApart;
    for (std::size_t n = 0; n < std::min(states.size(), theirs.size()); ++n)
      if ((states[n].position - theirs[n].position).norm() < apart)
        throw std::invalid_argument("the replay takes dynamic bodies that never touch, and " +
                                    scene.bodies[body].name + " comes within " + g3(apart) +
                                    " m of " + scene.bodies[j].name + " at step " +
                                    std::to_string(n));
  }
  return states;
}

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

// The body's drop under Simbody's Hunt-Crossley force (harness/core/simbody_contact.hpp), stepped
// as SemiExplicitEulerIntegrator steps it: the force from the step-start state, summed over every
// static box's top face the sphere is in, then v = phi*v + h*(g + f/m) (the damper in udot) and
// y += h*v. A sphere falling straight down, unturned and not spinning, nothing pushing it; a box
// under its brick contact (harness/oracles/simbody_brick_step.hpp).
std::vector<BodyState> hunt_crossley_states(const Scene& scene, std::size_t body,
                                            const ContactSolver&, double h, std::int64_t steps) {
  const Body& b = scene.bodies[body];
  if (b.shape == Shape::box) return simbody_brick_states(scene, body, h, steps);
  const Vec3& g = scene.world.gravity;
  if (b.shape != Shape::sphere || b.velocity.x() != 0.0 || b.velocity.z() != 0.0 ||
      !b.angular_velocity.isZero(0.0) || g.x() != 0.0 || g.z() != 0.0 || pushed(scene, body))
    throw std::invalid_argument(
        "Simbody's force law is predicted for a sphere dropped straight down, not spinning, with "
        "nothing but gravity and its floor acting");
  const SimbodyContact c = simbody_contact(scene, h);
  const double phi = std::exp(-scene.world.damping_rate * h);
  std::vector<BodyState> out{{b.position, b.velocity}};
  double y = b.position.y(), v = b.velocity.y();
  for (std::int64_t n = 1; n <= steps; ++n) {
    double f = 0.0;
    for (const Body& floor : scene.bodies)
      if (floor.is_static && floor.shape == Shape::box)
        if (const double depth = floor.position.y() + floor.half_extents.y() - (y - b.radius);
            depth > 0.0)
          f += std::max(hunt_crossley_force(c, b.radius, depth, -v), 0.0);
    v = phi * v + h * (g.y() + f / b.mass);
    y += h * v;
    out.push_back({Vec3(b.position.x(), y, b.position.z()), Vec3(0.0, v, 0.0)});
  }
  return out;
}

}  // namespace

std::vector<BodyState> replayed_states(const Scene& scene, std::size_t body,
                                       const ContactSolver& solver, double h, std::int64_t steps,
                                       const Trajectory* run) {
  if ((solver.kind == ContactSolverKind::box2d_2_4 ||
       solver.kind == ContactSolverKind::chipmunk_7) &&
      !is_planar(scene))
    throw std::invalid_argument("the replay is planar (a 2-D engine's), and the scene is not");
  switch (solver.kind) {
    case ContactSolverKind::box2d_2_4:
      return replay_alone(box2d_states, scene, body, solver, h, steps);
    case ContactSolverKind::chipmunk_7:
      return replay_alone(chipmunk_states, scene, body, solver, h, steps);
    case ContactSolverKind::mujoco_2_2:
      return mujoco_states(scene, body, h, steps, run);
    case ContactSolverKind::hunt_crossley:
      return replay_alone(hunt_crossley_states, scene, body, solver, h, steps, true);
    case ContactSolverKind::exact:
    case ContactSolverKind::bullet_3:
    case ContactSolverKind::sequential_impulses:
    case ContactSolverKind::soft:
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
