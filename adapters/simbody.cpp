// Adapter for Simbody 3.7 (Debian's build, double), with its fixed-step semi-explicit Euler
// integrator: Simbody has no world step; a MultibodySystem is advanced by an Integrator.
//
// Mapping (scene -> Simbody), read in Simbody 3.7's SimTKmath/Integrators/src
// (SemiExplicitEulerIntegrator.cpp, AbstractIntegratorRep.cpp) and Simbody/include:
//   body                -> a MobilizedBody::Free on Ground carrying Body::Rigid(MassProperties(m,
//                          0, Inertia(Ixx, Iyy, Izz))): the scene's mass and principal moments.
//                          Its u are (w, v), both in the Ground frame.
//   gravity g           -> Force::UniformGravity(g); Simbody has no gravity unless one is added.
//   damping rate k      -> Force::MobilityLinearDamper(c) on each translational u, a force -c*v
//   with
//                          c = m*(1 - exp(-k*h))/h; angular k_a likewise on the rotational u with
//                          c_a = I*(1 - exp(-k_a*h))/h (run only where that is a scalar decay:
//                          k_a = 0, or a spin about z, a principal axis; cannot_run).
//   law                 -> SemiExplicitEulerIntegrator(system, h) (fixed step, no error control):
//                          attemptDAEStep does u1 = u0 + h*udot(q0, u0), then q1 = q0 + h*N(q0)*u1
//                          and projects q (the quaternion back to unit length). With the damper
//                          in udot: v1 = (1 - h*c/m)*v0 + h*a = phi*v0 + h*a, then x1 = x0 + h*v1:
//                          DampingOrder::BeforeForces. Rotation: the gyroscopic term in udot at
//                          the step start (explicit), the first-order quaternion update with the
//                          new w, normalised: explicit/first-order.
//   force, torque       -> a Force::Custom reading this step's values (world frame, at the body
//                          origin). Simbody computes udot(q0, u0) when the previous step ends,
//                          before the harness sets the next step's forces, so a step whose forces
//                          differ from the last step's first re-initialises the integrator from
//                          its own state (Integrator::initialize realises it again, with this
//                          step's forces); the state itself is carried over unchanged.
//   one step            -> stepTo(n*h) (after initialize(state), a first call reports the start of
//                          the interval and a second takes the step). takeOneStep steps to tMax
//                          when it lies within [0.95, 1.001]*h of t0 (AbstractIntegratorRep.cpp),
//                          so each call is one step of n*h - (n - 1)*h: h up to the rounding of
//                          n*h (relative 1e-16 x n), with no tiny extra steps.
//   static body         -> no mobilized body: read back at its position, at rest.
//   position, velocity  -> setQToFitTransform, setUToFitVelocity; read with getBodyOriginLocation,
//                          getBodyOriginVelocity, the Free mobilizer's quaternion q[0..3] over its
//                          norm, and getBodyAngularVelocity.
// Contacts (Simbody/src/HuntCrossleyForce.cpp, GeneralContactSubsystem): spheres, each a
// ContactGeometry::Sphere, each static box's top face a ContactGeometry::HalfSpace, all in one
// contact set pushed by a HuntCrossleyForce, the compliant force law of
// harness/core/simbody_contact.hpp (its stiffness from the step, its dissipation from the scene's
// restitution). The integrator steps it as any force, so a bounce is predicted by that law
// stepped the same way (hunt_crossley_states). Boxes instead (a scene of boxes, no sphere): each a
// ContactGeometry::Brick under a CompliantContactSubsystem, whose BrickHalfSpacePenalty pushes at
// the vertices of the brick's face nearest the half-space (harness/core/simbody_contact.hpp),
// predicted by that force law stepped the same way (harness/oracles/simbody_brick_step.hpp).
// The Simbody calls themselves are in simbody_world.cpp (C++17; simbody_world.hpp says why).
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "adapters.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/simbody_contact.hpp"
#include "simbody_world.hpp"

namespace dropcheck {
namespace {

// simbody-rkm's accuracy: Simbody's own default, which it uses when none is set (IntegratorRep.h,
// initialize(): accuracyInUse = 1e-3 when the user gave none).
constexpr double kSimbodyDefaultAccuracy = 1e-3;

simbody::Vec to_array(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

Vec3 from_array(const simbody::Vec& v) {
  return {v[0], v[1], v[2]};
}

// Runs a Simbody call; its exceptions (SimTK::Exception) become EngineError.
template <typename F>
auto guarded(F&& call) {
  try {
    return call();
  } catch (const EngineError&) {
    throw;
  } catch (const std::exception& e) {
    throw EngineError(std::string("Simbody: ") + e.what());
  }
}

class SimbodyEngine final : public Engine {
 public:
  // accuracy 0: the fixed-step SemiExplicitEulerIntegrator ("simbody"); above 0: the
  // error-controlled RungeKuttaMersonIntegrator at that accuracy ("simbody-rkm").
  explicit SimbodyEngine(double accuracy = 0.0) : accuracy_(accuracy) {}

  EngineInfo info() const override {
    EngineInfo i;
    i.name = error_controlled() ? "simbody-rkm" : "simbody";
    i.version = "3.7";  // Debian's libsimbody-dev; Simbody.h defines no version macro
    i.scalar = Scalar::f64;
    if (error_controlled()) {
      i.capabilities = {.contacts = false, .planar_only = false, .rotation = Rotation::none};
      i.law = kErrorControlled;
      i.accuracy = accuracy_;
      i.damping_mapping =
          "MobilityLinearDamper c = m*k per translational u (the continuous drag); "
          "RungeKuttaMersonIntegrator, setAccuracy(" +
          g3(accuracy_) + "), a step ending at every h";
      return i;
    }
    i.capabilities = {.contacts = true,
                      .planar_only = false,
                      .rotation = Rotation::full,
                      .friction = true,
                      .restitution = true,
                      .spheres = true};
    i.law = DampingOrder::BeforeForces;
    i.contact_solver = {.kind = ContactSolverKind::hunt_crossley};
    i.contact_settings =
        "Hunt-Crossley point contacts (HuntCrossleyForce): spheres on static boxes' top faces as "
        "half-spaces; stiffness for a 20-step rest oscillation, dissipation for a rebound of e at "
        "the first impact, friction mu static and dynamic, transition velocity 0.01 m/s. Boxes: "
        "bricks (CompliantContactSubsystem, BrickHalfSpacePenalty), stiffness for a 20-step rest "
        "oscillation on four vertices, dissipation critical at rest (or a rebound of e), "
        "transition velocity 3*1.875*mu*|g|*h";
    i.rotation_law = {Gyroscopic::explicit_term, OrientationUpdate::first_order};
    i.damping_mapping =
        "MobilityLinearDamper c = m*(1 - exp(-k*h))/h per translational u, I_i*(1 - exp(-k_a*h))/h "
        "per rotational u; SemiExplicitEulerIntegrator(h)";
    return i;
  }

  std::int64_t engine_steps() const override {
    return error_controlled() && world_ ? world_->steps_taken() : 0;
  }

  bool set_accuracy(double a) override {
    if (!error_controlled()) return false;
    accuracy_ = a;
    return true;
  }

  std::string cannot_run(const Scene& scene) const override {
    if (std::string why = Engine::cannot_run(scene); !why.empty()) return why;
    if (scene.world.angular_damping_rate != 0.0 && needs_rotation(scene) && !spins_about_z(scene))
      return "angular damping: Simbody's damper is a torque -c*w per axis, a decay by one factor "
             "only for a spin about a principal axis";
    return scene.world.contacts ? contact_limit(scene) : std::string();
  }

  // The contacts the adapter maps, on one static box's top face (a half-space): spheres dropped
  // straight down from rest with the scene's restitution (a Hunt-Crossley bounce), or boxes
  // (bricks) that start apart; anything else the half-space and the force laws would not model
  // truly, or Simbody 3.7 tracks no contact for (brick-brick, sphere-brick).
  static std::string contact_limit(const Scene& scene) {
    int floors = 0, spheres = 0, boxes = 0;
    for (const Body& b : scene.bodies) {
      if (b.is_static && b.shape != Shape::box)
        return "contacts: Simbody's adapter maps static boxes only";
      floors += b.is_static;
      spheres += !b.is_static && b.shape == Shape::sphere;
      boxes += !b.is_static && b.shape == Shape::box;
    }
    if (floors != 1) return "contacts: Simbody's adapter maps one floor (a half-space)";
    if (spheres > 0 && boxes > 0)
      return "contacts: Simbody 3.7 tracks no sphere-brick contact (ContactTrackerSubsystem)";
    return boxes > 0 ? brick_limit(scene) : sphere_limit(scene);
  }

  // Bricks: any motion, but never one over another (across gravity, their reaches overlap), whose
  // contact Simbody would not see.
  static std::string brick_limit(const Scene& scene) {
    const Vec3& g = scene.world.gravity;
    const Vec3 down = g.norm() > 0.0 ? Vec3(g.normalized()) : Vec3::Zero();
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
      for (std::size_t j = i + 1; j < scene.bodies.size(); ++j) {
        const Body& a = scene.bodies[i];
        const Body& b = scene.bodies[j];
        const Vec3 d = a.position - b.position;
        if (!a.is_static && !b.is_static &&
            (d - d.dot(down) * down).norm() < a.half_extents.norm() + b.half_extents.norm())
          return "contacts: Simbody 3.7 tracks a brick against a half-space only (no "
                 "brick-brick contact), and " +
                 a.name + " starts over or within reach of " + b.name;
      }
    return {};
  }

  static std::string sphere_limit(const Scene& scene) {
    const Vec3& g = scene.world.gravity;
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      if (!b.is_static &&
          (!b.velocity.isZero(0.0) || !b.angular_velocity.isZero(0.0) || pushed(scene, i)))
        return "contacts: Simbody's adapter maps a sphere dropped from rest (a Hunt-Crossley "
               "bounce); a thrown, spinning or pushed sphere is not mapped";
    }
    if (g.x() != 0.0 || g.z() != 0.0 || scene.world.damping_rate != 0.0)
      return "contacts: Simbody's adapter maps a sphere's drop under gravity straight down, "
             "undamped";
    if (!scene_material(scene).restitution)
      return "contacts: Simbody's adapter maps a sphere's bounce (a restitution set): its "
             "compliant contact sinks and rebounds where a landing rests";
    return {};
  }

  void load(const Scene& scene, double h) override {
    world_.reset();
    simbody::WorldSpec spec{to_array(scene.world.gravity), scene.world.damping_rate,
                            scene.world.angular_damping_rate, h};
    spec.accuracy = accuracy_;
    if (scene.world.contacts) {
      const SimbodyContact c = simbody_contact(scene, h);
      spec.contact = {.on = true,
                      .bricks = c.bricks,
                      .stiffness = c.stiffness,
                      .dissipation = c.dissipation,
                      .friction = c.friction,
                      .transition_velocity = c.transition_velocity};
    }
    std::vector<simbody::BodySpec> bodies;
    for (const Body& b : scene.bodies) {
      const Quat& q = b.orientation;
      bodies.push_back({b.is_static,
                        b.mass,
                        to_array(inertia_of(b)),
                        to_array(b.position),
                        to_array(b.velocity),
                        {q.w(), q.x(), q.y(), q.z()},
                        to_array(b.angular_velocity),
                        b.shape == Shape::sphere ? b.radius : 0.0,
                        to_array(b.half_extents)});
    }
    world_ = guarded([&] { return std::make_unique<simbody::World>(spec, bodies); });
    bodies_ = scene.bodies.size();
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t i = 0; i < bodies_; ++i) world_->set_force(i, to_array(forces[i]));
  }

  void set_torques(std::span<const Vec3> torques) override {
    for (std::size_t i = 0; i < bodies_; ++i) world_->set_torque(i, to_array(torques[i]));
  }

  void step() override {
    guarded([&] {
      world_->step();
      return 0;
    });
  }

  // Seconds of `steps` integrator steps alone, without re-initialising (forces never change
  // there): bare_step_loop in adapters.hpp.
  double bare_seconds(std::int64_t steps) {
    const auto start = std::chrono::steady_clock::now();
    for (std::int64_t n = 0; n < steps; ++n) world_->bare_step();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  void read(std::span<BodyState> out) const override {
    for (std::size_t i = 0; i < bodies_; ++i) {
      const simbody::BodyMotion r = world_->motion(i);
      out[i] = {from_array(r.position), from_array(r.velocity)};
    }
  }

  void read_rotation(std::span<RotationState> out) const override {
    for (std::size_t i = 0; i < bodies_; ++i) {
      const simbody::BodyTurn r = world_->turn(i);
      const auto& q = r.orientation;
      out[i] = {Quat(q[0], q[1], q[2], q[3]), from_array(r.angular_velocity)};
    }
  }

 private:
  bool error_controlled() const { return accuracy_ > 0.0; }

  double accuracy_ = 0.0;
  std::unique_ptr<simbody::World> world_;
  std::size_t bodies_ = 0;
};

}  // namespace

std::unique_ptr<Engine> make_simbody() {
  return std::make_unique<SimbodyEngine>();
}

std::unique_ptr<Engine> make_simbody_rkm() {
  return std::make_unique<SimbodyEngine>(kSimbodyDefaultAccuracy);
}

double bare_seconds_simbody(const Scene& scene, double h) {
  SimbodyEngine e;
  e.load(scene, h);
  return e.bare_seconds(step_count(scene, h));
}

double bare_seconds_simbody_rkm(const Scene& scene, double h) {
  SimbodyEngine e(kSimbodyDefaultAccuracy);
  e.load(scene, h);
  return e.bare_seconds(step_count(scene, h));
}

}  // namespace dropcheck
