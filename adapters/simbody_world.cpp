// Simbody 3.7 calls of adapters/simbody.cpp (compiled as C++17: simbody_world.hpp says why). The
// mapping and the law are described at the top of adapters/simbody.cpp.
#include "simbody_world.hpp"

// GCC 12 reports array bounds inside Simbody's Vec and Row templates when a Transform is built
// from a Rotation (a false positive of its -Warray-bounds on Simbody's packed matrix storage).
#pragma GCC diagnostic ignored "-Warray-bounds"
#include <Simbody.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace dropcheck::simbody {
namespace {

SimTK::Vec3 to_sim(const Vec& v) {
  return {v[0], v[1], v[2]};
}

Vec from_sim(const SimTK::Vec3& v) {
  return {v[0], v[1], v[2]};
}

// This step's external forces and torques (world frame), one per scene body.
struct Applied {
  std::vector<SimTK::MobilizedBodyIndex> index;  // invalid for a static body
  std::vector<SimTK::Vec3> force, torque;
  // The forces and torques Simbody last computed udot with (at the end of the last step).
  std::vector<SimTK::Vec3> used_force, used_torque;

  bool changed() const { return force != used_force || torque != used_torque; }
};

// Applies `Applied` at each body's origin.
class AppliedForce final : public SimTK::Force::Custom::Implementation {
 public:
  explicit AppliedForce(const Applied& applied) : applied_(applied) {}
  void calcForce(const SimTK::State&, SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                 SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector&) const override {
    for (std::size_t i = 0; i < applied_.index.size(); ++i)
      if (applied_.index[i].isValid())
        body_forces[applied_.index[i]] += SimTK::SpatialVec(applied_.torque[i], applied_.force[i]);
  }
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0.0; }

 private:
  const Applied& applied_;
};

// The damper coefficient that decays a mobility of inertia `inertia` by phi = exp(-rate*h) per
// step: udot = -c/inertia*u, so one explicit step multiplies u by 1 - h*c/inertia = phi. With
// h = 0 (an error-controlled integrator, no step of its own), the continuous drag c = inertia*k.
double damper(double inertia, double rate, double h) {
  return h == 0.0 ? inertia * rate : inertia * -std::expm1(-rate * h) / h;
}

}  // namespace

struct World::Impl {
  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter{system};
  SimTK::GeneralForceSubsystem forces{system};
  std::vector<SimTK::MobilizedBody> bodies;  // Ground for a static body
  std::vector<Vec> static_positions;
  Applied applied;
  std::unique_ptr<SimTK::GeneralContactSubsystem> contacts;
  std::unique_ptr<SimTK::ContactTrackerSubsystem> tracker;
  std::unique_ptr<SimTK::CompliantContactSubsystem> compliant;
  std::unique_ptr<SimTK::Integrator> integrator;
  double h = 0.0;
  std::int64_t n = 0;  // steps taken

  void add_body(const WorldSpec& world, const BodySpec& b) {
    // What one velocity update spans (none for an error-controlled integrator).
    const double step = world.accuracy > 0.0 ? 0.0 : world.two_half_steps ? h / 2 : h;
    static_positions.push_back(b.position);
    applied.force.emplace_back(0);
    applied.torque.emplace_back(0);
    applied.used_force.emplace_back(0);
    applied.used_torque.emplace_back(0);
    if (b.is_static) {
      bodies.push_back(matter.Ground());
      applied.index.emplace_back();
      return;
    }
    const SimTK::Body::Rigid rigid(SimTK::MassProperties(
        b.mass, SimTK::Vec3(0), SimTK::Inertia(b.inertia[0], b.inertia[1], b.inertia[2])));
    SimTK::MobilizedBody::Free free(matter.Ground(), SimTK::Transform(), rigid, SimTK::Transform());
    // u = (w, v), both in Ground: rotational mobilities 0..2, translational 3..5.
    for (int axis = 0; axis < 3; ++axis) {
      if (world.damping_rate != 0.0)
        SimTK::Force::MobilityLinearDamper(forces, free, SimTK::MobilizerUIndex(3 + axis),
                                           damper(b.mass, world.damping_rate, step));
      if (world.angular_damping_rate != 0.0)
        SimTK::Force::MobilityLinearDamper(
            forces, free, SimTK::MobilizerUIndex(axis),
            damper(b.inertia[axis], world.angular_damping_rate, step));
    }
    applied.index.push_back(free.getMobilizedBodyIndex());
    bodies.push_back(free);
  }

  // Every dynamic box a Brick and every static box's top face a half-space (Simbody's x > 0 turned
  // to y < top), one material, under a CompliantContactSubsystem: its BrickHalfSpacePenalty pushes.
  void add_bricks(const ContactSpec& c, const std::vector<BodySpec>& specs) {
    tracker = std::make_unique<SimTK::ContactTrackerSubsystem>(system);
    compliant = std::make_unique<SimTK::CompliantContactSubsystem>(system, *tracker);
    compliant->setTransitionVelocity(c.transition_velocity);
    const SimTK::ContactMaterial material(c.stiffness, c.dissipation, c.friction, c.friction, 0.0);
    for (std::size_t i = 0; i < specs.size(); ++i) {
      const BodySpec& b = specs[i];
      if (b.radius > 0.0) continue;
      if (b.is_static) {
        const SimTK::Vec3 top(b.position[0], b.position[1] + b.half_extents[1], b.position[2]);
        matter.updGround().updBody().addContactSurface(
            SimTK::Transform(SimTK::Rotation(-SimTK::Pi / 2, SimTK::ZAxis), top),
            SimTK::ContactSurface(SimTK::ContactGeometry::HalfSpace(), material));
      } else {
        bodies[i].updBody().addContactSurface(
            SimTK::Transform(),
            SimTK::ContactSurface(SimTK::ContactGeometry::Brick(to_sim(b.half_extents)), material));
      }
    }
  }

  // One contact set of every sphere and every static box's top face (a half-space, Simbody's x > 0
  // turned to y < top), pushed by a HuntCrossleyForce with one material for all.
  void add_contacts(const ContactSpec& c, const std::vector<BodySpec>& specs) {
    contacts = std::make_unique<SimTK::GeneralContactSubsystem>(system);
    const SimTK::ContactSetIndex set = contacts->createContactSet();
    for (std::size_t i = 0; i < specs.size(); ++i) {
      const BodySpec& b = specs[i];
      const SimTK::Vec3 at = b.is_static ? to_sim(b.position) : SimTK::Vec3(0);
      if (b.radius > 0.0) {
        contacts->addBody(set, bodies[i], SimTK::ContactGeometry::Sphere(b.radius),
                          SimTK::Transform(at));
      } else if (b.is_static) {
        const SimTK::Vec3 top(b.position[0], b.position[1] + b.half_extents[1], b.position[2]);
        contacts->addBody(set, bodies[i], SimTK::ContactGeometry::HalfSpace(),
                          SimTK::Transform(SimTK::Rotation(-SimTK::Pi / 2, SimTK::ZAxis), top));
      }
    }
    SimTK::HuntCrossleyForce force(forces, *contacts, set);
    for (int k = 0; k < contacts->getNumBodies(set); ++k)
      force.setBodyParameters(SimTK::ContactSurfaceIndex(k), c.stiffness, c.dissipation, c.friction,
                              c.friction, 0.0);
    force.setTransitionVelocity(c.transition_velocity);
  }

  // stepTo(n*h) takes one step of n*h - (n - 1)*h: takeOneStep steps to tMax when it lies within
  // [0.95, 1.001]*h of t0 (AbstractIntegratorRep.cpp).
  void advance() {
    ++n;
    const double t1 = static_cast<double>(n) * h;
    integrator->stepTo(t1);
    if (integrator->getTime() != t1)
      throw std::runtime_error("Simbody stepped to t = " + std::to_string(integrator->getTime()) +
                               " instead of " + std::to_string(t1));
  }
};

World::World(const WorldSpec& world, const std::vector<BodySpec>& bodies)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.h = world.h;
  SimTK::Force::UniformGravity(m.forces, m.matter, to_sim(world.gravity), 0.0);
  for (const BodySpec& b : bodies) m.add_body(world, b);
  if (world.contact.on && world.contact.bricks)
    m.add_bricks(world.contact, bodies);
  else if (world.contact.on)
    m.add_contacts(world.contact, bodies);
  SimTK::Force::Custom(m.forces, new AppliedForce(m.applied));
  m.system.realizeTopology();
  SimTK::State state = m.system.getDefaultState();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const BodySpec& b = bodies[i];
    if (b.is_static) continue;
    const auto& q = b.orientation;
    const SimTK::Rotation r(SimTK::Quaternion(q[0], q[1], q[2], q[3]));
    m.bodies[i].setQToFitTransform(state, SimTK::Transform(r, to_sim(b.position)));
    m.bodies[i].setUToFitVelocity(
        state, SimTK::SpatialVec(to_sim(b.angular_velocity), to_sim(b.velocity)));
  }
  if (world.accuracy > 0.0) {
    m.integrator = std::make_unique<SimTK::RungeKuttaMersonIntegrator>(m.system);
    m.integrator->setAccuracy(world.accuracy);
  } else if (world.two_half_steps) {
    m.integrator = std::make_unique<SimTK::SemiExplicitEuler2Integrator>(m.system);
    m.integrator->setFixedStepSize(m.h);  // no error control: every step is h
  } else {
    m.integrator = std::make_unique<SimTK::SemiExplicitEulerIntegrator>(m.system, m.h);
  }
  m.integrator->setAllowInterpolation(false);
  m.integrator->initialize(state);
  m.integrator->stepTo(0.0);  // reports the start of the continuous interval; no step
}

World::~World() = default;

void World::set_force(std::size_t i, const Vec& force) {
  impl_->applied.force[i] = to_sim(force);
}

void World::set_torque(std::size_t i, const Vec& torque) {
  impl_->applied.torque[i] = to_sim(torque);
}

void World::step() {
  Impl& m = *impl_;
  // Simbody computed udot(q0, u0) when the last step ended, with the forces of that step. When
  // this step's differ, initialize() realises the same state again with them (and reports the
  // start of a continuous interval, which stepTo(t0) consumes). Forces that stay the same (none,
  // or constant ones) cost nothing: initialize() costs 80 us per step for one body.
  if (m.applied.changed()) {
    const SimTK::State state = m.integrator->getState();
    m.integrator->initialize(state);
    m.integrator->stepTo(state.getTime());
  }
  m.advance();
  m.applied.used_force = m.applied.force;
  m.applied.used_torque = m.applied.torque;
  for (SimTK::Vec3& f : m.applied.force) f = SimTK::Vec3(0);  // this step only
  for (SimTK::Vec3& t : m.applied.torque) t = SimTK::Vec3(0);
}

void World::bare_step() {
  impl_->advance();
}

BodyMotion World::motion(std::size_t i) const {
  const Impl& m = *impl_;
  if (!m.applied.index[i].isValid()) return {m.static_positions[i], {}};
  const SimTK::State& s = m.integrator->getState();
  const SimTK::MobilizedBody& b = m.bodies[i];
  return {from_sim(b.getBodyOriginLocation(s)), from_sim(b.getBodyOriginVelocity(s))};
}

// The orientation is the Free mobilizer's own quaternion, q[0..3] = (w, x, y, z) of its state,
// divided by its norm: Simbody lets that q drift off unit length between projections and turns
// the body by q/|q| (its rotation matrix). Cheaper than a quaternion rebuilt from the rotation
// matrix (getBodyRotation then convertRotationToQuaternion), which rounds it again.
long World::steps_taken() const {
  return impl_->integrator->getNumStepsTaken();
}

long World::steps_attempted() const {
  return impl_->integrator->getNumStepsAttempted();
}

BodyTurn World::turn(std::size_t i) const {
  const Impl& m = *impl_;
  if (!m.applied.index[i].isValid()) return {};
  const SimTK::State& s = m.integrator->getState();
  const SimTK::MobilizedBody::Free& b = SimTK::MobilizedBody::Free::downcast(m.bodies[i]);
  const SimTK::Vec7& q = b.getQ(s);
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  return {{q[0] / n, q[1] / n, q[2] / n, q[3] / n}, from_sim(b.getBodyAngularVelocity(s))};
}

}  // namespace dropcheck::simbody
