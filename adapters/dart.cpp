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
//   position, velocity  -> FreeJoint::setTransform (translation and rotation) and
//                          FreeJoint::setLinearVelocity (world frame); read back with
//                          BodyNode::getWorldTransform().translation() and getLinearVelocity().
//   force this step     -> BodyNode::addExtForce(F) (world frame, at the body origin) before the
//                          step; World::step(true) clears it after.
//   static body         -> no skeleton: read back at its position, at rest.
//   one step            -> World::step().
// Rotation (FreeJoint.cpp integratePositions, GenericJoint's implicit damping):
//   orientation q       -> FreeJoint::setTransform (rotation and translation); the joint stores
//                          it as a rotation vector, logMap(R) (Eigen's AngleAxis), and rebuilds
//                          R = expMapRot(p) from it every step
//   angular velocity w  -> FreeJoint::setAngularVelocity (world frame): the joint keeps R^T*w
//   torque this step    -> BodyNode::addExtTorque(tau) (world frame), cleared by World::step(true)
//   angular damping k_a -> setDampingCoefficient(i, I_i*(exp(k_a*h) - 1)/h) on DOFs 0, 1, 2
//                          (body axes), implicit as the translational ones: the order AfterForces
//   law                 -> the gyroscopic term at the step start (explicit), then
//                          R' = R*expMapRot(h*w_b): the exponential map, with the rounding of the
//                          rotation vector's round trip every step, which the own-law prediction
//                          repeats in double (harness/oracles/own_arithmetic.cpp,
//                          rotate_as_rotation_vector). Measured against a scratch replica of that
//                          round trip: 0 rad on a steady spin over 10000 steps at 1 ms, 5e-13 rad
//                          on a tumble; the world-frame translation of a tumbling body stays
//                          semi-implicit Euler to 7e-12 m after 4000 steps.
//   read back           -> BodyNode::getWorldTransform().linear() and getAngularVelocity()
//   rounding            -> the gyroscopic force comes from the spatial velocity (w, v_b) in body
//                          coordinates, v_b x m*v_b included: zero exactly, but it rounds to
//                          2*eps*m*|v|^2 of torque a step. On Gazebo's complex box at 1/60 (|v| up
//                          to 90 m/s, I_min 0.14) that is 2,540 ulps of |w| a step, and takes the
//                          replica 1e-8 rad from DART; with DART's own v_b in it, 6e-11 rad. The
//                          own-law tolerance counts it (RotationLaw::spatial_bias).
//
// Contacts, read in DART 6.12's dart/constraint/ContactConstraint.cpp and BoxedLcpConstraintSolver:
//   shapes              -> a BoxShape of the scene's full sides on each body, collided by DART's
//                          own detector (DARTCollisionDetector: box-box exact; the World's default,
//                          FCL, collides boxes as meshes, and threw incline_slide 0.018 m off at
//                          step 80 where the box crossed the floor mesh's diagonal); a static body
//                          is a Skeleton on a WeldJoint placed at its position.
//   friction mu         -> setFrictionCoeff(mu) on every shape; a contact takes the smaller of its
//                          two (std::min), so every contact's is the scene's mu. Unset: DART's
//                          default 1.0.
//   friction model      -> two tangent directions (getTangentBasisMatrixODE: z and x under a
//                          normal along y), each bounded by mu times the contact's normal impulse
//                          (lo/hi = -+mu, findex 0) in one Dantzig boxed LCP: the box pyramid,
//                          solved exactly but for its regularisation, which adds CFM = 1e-5 times
//                          each diagonal entry (getVelocityChange): relative_cfm below, the law
//                          of harness/core/relative_cfm.hpp. Measured against it (scratch runs of
//                          a unit cube, 240 steps): the sink to 8e-14 m (level, 1/60) and 2.9e-13 m
//                          (30 degree incline); a slide that never stops to 4.9e-11 m (incline,
//                          1/60) and 2.5e-13 m (level, 1/240). Where the box stops, its stuck rows
//                          leave 1.09 times cfm/(1 + cfm) of the slip on a 20 degree incline (the
//                          normal rows' regularisation takes part): the creep runs 5e-8 m/s past
//                          the law's, 8.5e-7 m over 240 steps.
//   push-out            -> ERP 0.01 of the depth per step, capped at 1e-3 m/s (DART_ERP,
//                          DART_MAX_ERV): relative_cfm's max_push. A box that lands from a height
//                          stops up to |v|*h deep and climbs out at the cap less cfm times the
//                          step's fall: drop_on_floor_undamped at 1/60 lands 0.218 m deep and
//                          rises at 0.998367e-3 m/s, so that a landing takes minutes to rest. The
//                          landing check follows that climb step by step
//                          (harness/oracles/landing.hpp climb_path).
//   stack               -> box-box contacts at the four corners of the overlap of two faces, one
//                          Dantzig LCP for all: with each load shared by its four corners, the
//                          column is stepped exactly by harness/oracles/stack.hpp
//                          relative_cfm_column (each corner row's diagonal entry 1/m_a + 1/m_b plus
//                          the two boxes' turning; DART's impulse response is the plain mass
//                          matrix, the joint damping scaling none of it). Measured on stack_rest at
//                          1/60: 8.9e-16 m off it at every step. An off-centre column (unequal
//                          corners) is not run.
//   restitution e       -> setRestitutionCoeff(e) on a moving body's shape, 1 on a static one:
//                          a contact takes the product of its two (computeRestitutionCoefficient),
//                          e exactly against a static body; two moving bodies with restitution
//                          would meet at e^2 and are not run (contact_limit). The contact bounces
//                          when the product exceeds 1e-3 (DART_RESTITUTION_COEFF_THRESHOLD; the
//                          bounce law leaves that out: an e <= 1e-3 would need an approach over
//                          100 m/s to matter). In
//                          getInformation, the normal row's target is e times the approach its
//                          LCP sees, -J*v after integrateVelocities (the step's gravity applied),
//                          when that rebound exceeds 0.1 m/s (DART_BOUNCING_VELOCITY_THRESHOLD) and
//                          the capped push-out, at most 100 m/s (DART_MAX_BOUNCING_VELOCITY); the
//                          row then stops 1/(1 + cfm) of the way there: bounce_law below.
//   sphere              -> a SphereShape of its radius; DARTCollisionDetector's sphere-box test
//                          (collideSphereBox) reports a contact at penetration >= 0, so a touch is
//                          one, at depth radius - (distance from the centre to the box).
#include <algorithm>
#include <cmath>
#include <dart/collision/dart/DARTCollisionDetector.hpp>
#include <dart/config.hpp>
#include <dart/constraint/ConstraintSolver.hpp>
#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/BoxShape.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/ShapeNode.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/dynamics/SphereShape.hpp>
#include <dart/dynamics/WeldJoint.hpp>
#include <dart/simulation/World.hpp>
#include <memory>
#include <string>
#include <vector>

#include "adapters.hpp"
#include "harness/core/engine_writer.hpp"

namespace dropcheck {
namespace {

// Whether boxes a and b overlap in the x-z plane (one above the other) or touch.
bool stacked_or_touching(const Body& a, const Body& b) {
  const Vec3 gap = (a.position - b.position).cwiseAbs() - (a.half_extents + b.half_extents);
  return (gap.x() < 0.0 && gap.z() < 0.0) || gap.maxCoeff() <= 0.0;
}

// Whether a and b stand one on the other, centred, the upper one's bottom at or above the lower
// one's top: a column whose four corner contacts share each load equally.
bool centred_stack(const Body& a, const Body& b) {
  const Body& upper = a.position.y() > b.position.y() ? a : b;
  const Body& lower = &upper == &a ? b : a;
  return upper.position.x() == lower.position.x() && upper.position.z() == lower.position.z() &&
         upper.position.y() - upper.half_extents.y() >= lower.position.y() + lower.half_extents.y();
}

// Why DART's contacts in `scene` are not judged, or "": restitution only on one sphere dropped from
// rest (no restitution between two moving bodies),
// no dynamic body may start beside or off-centre on another (the stack law is a centred column's;
// bodies that meet later, sliding into each other, would fail their checks
// rather than pass wrongly), and no force may push one (the climb path of a landing takes gravity
// and damping only).
std::string contact_limit(const Scene& scene) {
  const auto moving = std::count_if(scene.bodies.begin(), scene.bodies.end(),
                                    [](const Body& b) { return !b.is_static; });
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Body& b = scene.bodies[i];
    if (b.is_static) continue;
    if (pushed(scene, i))
      return "a pushed body among contacts: DART's landing is judged under gravity and damping "
             "alone";
    if (scene_material(scene).restitution && moving > 1)
      return "restitution among two moving bodies: DART multiplies the two shapes' coefficients, "
             "so they would meet at e^2";
    if (scene_material(scene).restitution &&
        (b.shape != Shape::sphere || b.velocity != Vec3::Zero()))
      return "restitution on a box or a launched sphere: DART's rebound is judged on a sphere "
             "dropped from rest (its bounce law), a landing by a climb path without restitution";
    for (const Body& o : scene.bodies)
      if (&o != &b && !o.is_static && stacked_or_touching(b, o) && !centred_stack(b, o))
        return "moving boxes that touch side by side or stand off-centre on each other: the "
               "stack check models DART's regularised contacts in a centred column only";
  }
  return {};
}

// DART's contact constants (ContactConstraint.cpp): DART_CFM, DART_ERP, DART_MAX_ERV.
constexpr RelativeCfm kContact{.cfm = 1e-5, .erp = 0.01, .max_push = 1e-3};

class DartEngine final : public Engine {
 public:
  EngineInfo info() const override {
    EngineInfo i;
    i.name = "dart";
    i.version = DART_VERSION;
    i.scalar = Scalar::f64;
    i.capabilities = {.contacts = true,
                      .planar_only = false,
                      .rotation = Rotation::full,
                      .friction = true,
                      .restitution = true,
                      .spheres = true};
    i.law = DampingOrder::AfterForces;
    i.rotation_law = {.gyroscopic = Gyroscopic::explicit_term,
                      .orientation = OrientationUpdate::exponential_map,
                      .rotation_vector = true,
                      .spatial_bias = true};
    i.friction_model = FrictionModel::box_pyramid;
    i.relative_cfm = kContact;
    // The column is stepped exactly (relative_cfm_column): held to its path to 1e-12 m (measured
    // 8.9e-16 m on stack_rest), no drift (measured 2.4e-16 m). Still: the column nears its steady
    // sink by about (1 - erp) a step, so 3 s in it still moves (erp/h)*sink*0.99^180, 9.6e-7 m/s on
    // stack_rest (measured 9.5e-7 m/s and 1.1e-6 m over the last 2 s).
    i.stack_law = {.sink_bound = 1e-12, .drift_bound = 1e-12, .still_bound = 1e-5};
    i.bounce_law = {.erp = kContact.erp,
                    .max_push = kContact.max_push,
                    .threshold = 0.1,
                    .touching = true,
                    .free_approach = true,
                    .threshold_on_rebound = true,
                    .max_rebound = 100.0,
                    .cfm = kContact.cfm};
    i.contact_settings =
        "World::step with DART's own collision detector; box and sphere shapes, friction 1.0 or "
        "the scene's (the smaller of two), restitution 0 or the scene's (a moving body's e times "
        "a static body's 1); boxed LCP (Dantzig), ERP 0.01, max error reduction velocity 1e-3 "
        "m/s, CFM 1e-5 of each diagonal entry";
    i.damping_mapping =
        "FreeJoint translational damping d = m*(exp(k*h) - 1)/h (implicit: v = (v + a*h)/(1 + "
        "h*d/m))";
    return i;
  }

  // A scene with contacts runs when each moving box meets static bodies alone and no force pushes
  // it (contact_limit; see the mapping above).
  std::string cannot_run(const Scene& scene) const override {
    if (std::string why = Engine::cannot_run(scene); !why.empty()) return why;
    return scene.world.contacts ? contact_limit(scene) : std::string();
  }

  void load(const Scene& scene, double h) override {
    h_ = h;
    world_ = dart::simulation::World::create("dropcheck");
    world_->setGravity(scene.world.gravity);
    world_->setTimeStep(h);
    world_->getConstraintSolver()->setCollisionDetector(
        dart::collision::DARTCollisionDetector::create());
    bodies_.assign(scene.bodies.size(), nullptr);
    positions_.clear();
    for (const Body& b : scene.bodies) positions_.push_back(b.position);
    const Material material = scene_material(scene);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      dart::dynamics::BodyNode* node = nullptr;
      if (!b.is_static)
        node = bodies_[i] = add_body(b, scene, i);
      else if (scene.world.contacts)
        node = add_static(b, i);
      if (scene.world.contacts) add_shape(*node, b, material);
    }
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t i = 0; i < bodies_.size(); ++i)
      if (bodies_[i]) bodies_[i]->addExtForce(forces[i]);
  }

  void set_torques(std::span<const Vec3> torques) override {
    for (std::size_t i = 0; i < bodies_.size(); ++i)
      if (bodies_[i]) bodies_[i]->addExtTorque(torques[i]);
  }

  void read_rotation(std::span<RotationState> out) const override {
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      out[i] = RotationState{};
      if (!bodies_[i]) continue;
      out[i].orientation = Quat(bodies_[i]->getWorldTransform().linear());
      out[i].angular_velocity = bodies_[i]->getAngularVelocity();
    }
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
  // A static body: a Skeleton welded to the world at the body's position.
  dart::dynamics::BodyNode* add_static(const Body& b, std::size_t index) {
    auto skeleton = dart::dynamics::Skeleton::create("static" + std::to_string(index));
    auto [joint, node] = skeleton->createJointAndBodyNodePair<dart::dynamics::WeldJoint>();
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = b.position;
    joint->setTransformFromParentBodyNode(pose);
    world_->addSkeleton(skeleton);
    return node;
  }

  // The body's box or sphere on its node, with the scene's friction and restitution when it sets
  // them (a static body's restitution 1: the contact's product is the moving body's e).
  void add_shape(dart::dynamics::BodyNode& node, const Body& b, const Material& material) {
    dart::dynamics::ShapePtr geometry;
    if (b.shape == Shape::sphere)
      geometry = std::make_shared<dart::dynamics::SphereShape>(b.radius);
    else
      geometry = std::make_shared<dart::dynamics::BoxShape>(2.0 * b.half_extents);
    auto* shape =
        node.createShapeNodeWith<dart::dynamics::CollisionAspect, dart::dynamics::DynamicsAspect>(
            geometry);
    if (material.friction) shape->getDynamicsAspect()->setFrictionCoeff(*material.friction);
    if (material.restitution)
      shape->getDynamicsAspect()->setRestitutionCoeff(b.is_static ? 1.0 : *material.restitution);
  }

  dart::dynamics::BodyNode* add_body(const Body& b, const Scene& scene, std::size_t index) {
    auto skeleton = dart::dynamics::Skeleton::create("body" + std::to_string(index));
    auto [joint, node] = skeleton->createJointAndBodyNodePair<dart::dynamics::FreeJoint>();
    const Vec3 moments = inertia_of(b);
    node->setInertia(dart::dynamics::Inertia(b.mass, Vec3::Zero(), moments.asDiagonal()));
    const double d = b.mass * std::expm1(scene.world.damping_rate * h_) / h_;
    for (std::size_t dof = 3; dof < 6; ++dof) joint->setDampingCoefficient(dof, d);
    const double c_a = std::expm1(scene.world.angular_damping_rate * h_) / h_;
    for (std::size_t dof = 0; dof < 3; ++dof) joint->setDampingCoefficient(dof, moments[dof] * c_a);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = b.orientation.toRotationMatrix();
    pose.translation() = b.position;
    joint->setTransform(pose);
    joint->setLinearVelocity(b.velocity);
    joint->setAngularVelocity(b.angular_velocity);
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
