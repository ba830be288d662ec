// The Simbody side of adapters/simbody.cpp, behind a plain interface: Simbody 3.7's headers do not
// compile as C++20 (its index types' operator== becomes ambiguous under C++20's rewritten
// comparisons, simmath/internal/ContactGeometry.h), so every Simbody call lives in
// simbody_world.cpp, compiled as C++17, and this header includes neither Simbody nor dropcheck.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

namespace dropcheck::simbody {

using Vec = std::array<double, 3>;

struct BodySpec {
  bool is_static = false;
  double mass = 1.0;
  Vec inertia{};  // principal moments, body frame
  Vec position{}, velocity{};
  std::array<double, 4> orientation{1.0, 0.0, 0.0, 0.0};  // (w, x, y, z), body to world
  Vec angular_velocity{};                                 // world frame
  double radius = 0.0;  // > 0: a sphere's contact surface (WorldSpec::contact)
  Vec half_extents{};   // a box's: a static box's top face is a contact half-space, a dynamic
                        // box a brick (ContactSpec::bricks)
};

// Hunt-Crossley point contacts (HuntCrossleyForce on a GeneralContactSubsystem): every sphere and
// every static box's top face, all with the same material. With `bricks`, every dynamic box a
// ContactGeometry::Brick and every static box's top face a half-space under a
// CompliantContactSubsystem (its BrickHalfSpacePenalty), one material for all.
struct ContactSpec {
  bool on = false;
  bool bricks = false;
  double stiffness = 0.0;    // E of each surface (of a brick's contact, k in N/m)
  double dissipation = 0.0;  // c of each surface, s/m
  double friction = 0.0;     // static and dynamic
  double transition_velocity = 0.01;
};

struct WorldSpec {
  Vec gravity{};
  double damping_rate = 0.0;          // k, 1/s, on every translational mobility
  double angular_damping_rate = 0.0;  // k_a, 1/s, on every rotational mobility
  double h = 1.0 / 60.0;
  // SemiExplicitEuler2Integrator at the fixed step h instead: each step takes one step of h and
  // two of h/2 and keeps the two halves (the Simbody integrator Gazebo's benchmark ran). Not an
  // engine of its own: tests/adapters/simbody_test.cpp reproduces Gazebo's published column with
  // it. Damping is then matched per half step.
  bool two_half_steps = false;
  // Above 0: RungeKuttaMersonIntegrator instead, error-controlled at this relative accuracy. It
  // picks its own steps and ends one at every multiple of h (interpolation off), and the damper
  // is the continuous drag c = m*k: it integrates the continuous model, not a per-step map.
  double accuracy = 0.0;
  ContactSpec contact{};
};

struct BodyMotion {
  Vec position{}, velocity{};
};

struct BodyTurn {
  std::array<double, 4> orientation{1.0, 0.0, 0.0, 0.0};  // (w, x, y, z)
  Vec angular_velocity{};                                 // world frame
};

// One scene as a Simbody MultibodySystem advanced by its fixed-step semi-explicit Euler
// integrator. Every call may throw std::exception (SimTK::Exception) on Simbody's errors.
class World {
 public:
  World(const WorldSpec& world, const std::vector<BodySpec>& bodies);
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // This step's force and torque on body i (world frame, at its origin); cleared by step().
  void set_force(std::size_t i, const Vec& force);
  void set_torque(std::size_t i, const Vec& torque);
  // One step of h with this step's forces (the integrator re-initialised from its own state when
  // they differ from the last step's).
  void step();
  // One step of h without re-initialising (forces that never change): the bare loop.
  void bare_step();
  // Body i's state after the last step (a static body: its position, at rest, unturned).
  BodyMotion motion(std::size_t i) const;
  BodyTurn turn(std::size_t i) const;
  // Steps the integrator has taken (and attempted, failures included) since it was built.
  long steps_taken() const;
  long steps_attempted() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dropcheck::simbody
