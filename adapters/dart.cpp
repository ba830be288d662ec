// Adapter for DART 6.12 (Debian's libdart-dev, double), the Dynamic Animation and Robotics Toolkit
// and Gazebo's fourth engine: each dynamic body is a Skeleton of one BodyNode on a FreeJoint.
//
// Mapping (scene -> DART), read in DART 6.12's dart/simulation/World.cpp,
// dart/dynamics/GenericJoint.hpp (detail/GenericJoint.hpp) and dart/dynamics/FreeJoint.cpp:
//   law                 -> World::step: for every skeleton computeForwardDynamics() and
//                          integrateVelocities(h) (v += h*a), then the constraint solver, then
//                          integratePositions(h) with the new velocity: semi-implicit Euler.
//   damping rate k      -> setDampingCoefficient(i, d) on the FreeJoint's three translational
//                          DOFs (3, 4, 5), d = m*(exp(k*h) - 1)/h. DART's joint damping is
//                          implicit: the damping force -d*v (GenericJoint::updateTotalForceDynamic)
//                          meets a projected articulated inertia with h*d added
//                          (updateInvProjArtInertiaImplicitDynamic), so a = (F - d*v)/(m + h*d)
//                          and v' = (v + h*F/m)/(1 + h*d/m) = phi*(v + h*F/m) with that d:
//                          DampingOrder::AfterForces, MuJoCo's form. The rotational DOFs keep
//                          DART's default damping 0.
//   gravity g           -> World::setGravity(g); DART's default is (0, 0, -9.81) (World.cpp).
//   step h              -> World::setTimeStep(h); DART's default is 0.001 s (World.cpp).
//   mass, inertia       -> BodyNode::setInertia(Inertia(m, 0, diag(I))): the scene's mass and
//                          principal moments, centre of mass at the body origin.
//   position, velocity  -> FreeJoint::setTransform (translation, identity rotation) and
//                          FreeJoint::setLinearVelocity (world frame); read back with
//                          BodyNode::getWorldTransform().translation() and getLinearVelocity().
//   force this step     -> BodyNode::addExtForce(F) (world frame, at the body origin) before the
//                          step; World::step(true) clears it after.
//   static body         -> no skeleton: read back at its position, at rest.
//   one step            -> World::step().
// Rotation: not run yet. Tried (2026-11-26): with the orientation, angular velocity, torque and
// rotational joint damping mapped as MuJoCo's are, `identify` names DART's rotation
// explicit/exp-map on Gazebo's tumble (8.9e-11 rad; runner-up 1.2e-4 rad away). But the FreeJoint
// keeps its orientation as a rotation vector (its positions' head, logMap(R), wrapping at pi) and
// rebuilds R from it every step; that round trip loses digits near a half turn: a spin at 5 rad/s
// for 10 s at 1 ms strays up to 1.2e-10 rad from the exact turn, jumping where the angle passes pi,
// and Gazebo's simple box ends 2.1e-7 rad off its member, beyond the own-law rounding budget. Until
// that rounding is modelled, a scene that needs rotation is not run. Contacts: not mapped (bodies
// carry no collision shapes): a scene with contacts is not run.
#include <dart/config.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/simulation/World.hpp>
#include <memory>
#include <string>
#include <vector>

#include "adapters.hpp"
#include "harness/core/engine_writer.hpp"

namespace dropcheck {
namespace {

class DartEngine final : public Engine {
 public:
  EngineInfo info() const override {
    EngineInfo i;
    i.name = "dart";
    i.version = DART_VERSION;
    i.scalar = Scalar::f64;
    i.capabilities = {.contacts = false, .planar_only = false, .rotation = Rotation::none};
    i.law = DampingOrder::AfterForces;
    i.damping_mapping =
        "FreeJoint translational damping d = m*(exp(k*h) - 1)/h (implicit: v = (v + a*h)/(1 + "
        "h*d/m))";
    return i;
  }

  void load(const Scene& scene, double h) override {
    h_ = h;
    world_ = dart::simulation::World::create("dropcheck");
    world_->setGravity(scene.world.gravity);
    world_->setTimeStep(h);
    bodies_.assign(scene.bodies.size(), nullptr);
    positions_.clear();
    for (const Body& b : scene.bodies) positions_.push_back(b.position);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
      if (!scene.bodies[i].is_static) bodies_[i] = add_body(scene.bodies[i], scene, i);
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t i = 0; i < bodies_.size(); ++i)
      if (bodies_[i]) bodies_[i]->addExtForce(forces[i]);
  }

  void step() override { world_->step(); }

  // Seconds of `steps` calls of World::step alone (bare_step_loop in adapters.hpp).
  double bare_seconds(std::int64_t steps) {
    const auto start = std::chrono::steady_clock::now();
    for (std::int64_t n = 0; n < steps; ++n) world_->step();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  void read(std::span<BodyState> out) const override {
    (void)write(StateWriter<false>(out.data()));  // the finite check is read_append's business
  }

  // Each state written once from DART's numbers and checked in the same pass.
  bool read_append(std::size_t, StateBuffer& out, StateUse use) const override {
    return append_states(out, bodies_.size(), use, [this](auto w) { return write(w); });
  }

 private:
  dart::dynamics::BodyNode* add_body(const Body& b, const Scene& scene, std::size_t index) {
    auto skeleton = dart::dynamics::Skeleton::create("body" + std::to_string(index));
    auto [joint, node] = skeleton->createJointAndBodyNodePair<dart::dynamics::FreeJoint>();
    const Vec3 moments = inertia_of(b);
    node->setInertia(dart::dynamics::Inertia(b.mass, Vec3::Zero(), moments.asDiagonal()));
    const double d = b.mass * std::expm1(scene.world.damping_rate * h_) / h_;
    for (std::size_t dof = 3; dof < 6; ++dof) joint->setDampingCoefficient(dof, d);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = b.position;
    joint->setTransform(pose);
    joint->setLinearVelocity(b.velocity);
    world_->addSkeleton(skeleton);
    return node;
  }

  // Puts every body's state in scene order into `w`; true when all are finite.
  template <typename Writer>
  bool write(Writer&& w) const {
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      if (!bodies_[i]) {
        const Vec3& p = positions_[i];
        w.put(p.x(), p.y(), p.z(), 0.0, 0.0, 0.0);
        continue;
      }
      const Vec3 x = bodies_[i]->getWorldTransform().translation();
      const Vec3 v = bodies_[i]->getLinearVelocity();
      w.put(x.x(), x.y(), x.z(), v.x(), v.y(), v.z());
    }
    return w.finish();
  }

  double h_ = 1.0 / 60.0;
  dart::simulation::WorldPtr world_;
  std::vector<dart::dynamics::BodyNode*> bodies_;  // indexed like Scene::bodies; null if static
  std::vector<Vec3> positions_;                    // the scene's positions (static bodies)
};

}  // namespace

std::unique_ptr<Engine> make_dart() {
  return std::make_unique<DartEngine>();
}

double bare_seconds_dart(const Scene& scene, double h) {
  DartEngine e;
  e.load(scene, h);
  return e.bare_seconds(step_count(scene, h));
}

}  // namespace dropcheck
