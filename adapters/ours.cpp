// Adapter for ours/ (the seed's engine), in f32 (`ours`, the seed's own scalar) and f64
// (`ours-f64`).
//
// Mapping (scene -> ours):
//   gravity g          -> World::gravity
//   damping rate k     -> World::linearDrag = exp(-k*h), the seed's per-step factor at this h
//   mass, position, v  -> Model::translation, RigidBody::{mass, velocity}; static -> isStatic
//   force this step    -> RigidBody::force (IntegrateLinearForce clears it)
//   contacts           -> World::collisions (ours/collision.hpp); each body's shape and extent
//                         -> Model::collider; the scene's friction and restitution (one value per
//                         scene) -> World::friction, ::restitution (0 when unset)
// Contacts (ours/collision.hpp): touching and overlapping pairs found at the step's start, resolved
// from the floor up with a Coulomb cone clamp and the restitution of the step-start approach, the
// overlap pushed out in position. Impulses act through the centre of mass, except a turned or
// turning box's, which act at the mean of its corners in the floor; such a box may share a contact
// scene with static boxes only.
#include <algorithm>
#include <chrono>
#include <vector>

#include "adapters.hpp"
#include "harness/core/engine_writer.hpp"
#include "ours/physics.hpp"

namespace dropcheck {
namespace {

template <typename T>
class OursEngine final : public Engine {
 public:
  EngineInfo info() const override {
    EngineInfo i;
    i.name = sizeof(T) == 4 ? "ours" : "ours-f64";
    i.version = "seed part III";
    i.scalar = sizeof(T) == 4 ? Scalar::f32 : Scalar::f64;
    i.capabilities = {.contacts = true,
                      .planar_only = false,
                      .rotation = Rotation::full,
                      .friction = true,
                      .restitution = true,
                      .spheres = true};
    i.law = DampingOrder::AfterForces;
    i.rotation_law = {Gyroscopic::explicit_term, OrientationUpdate::first_order};
    i.arithmetic = DampingForm::phi_multiply;  // ours/physics.hpp, copied by own_arithmetic.cpp
    i.damping_mapping = "linearDrag f = exp(-k*h) per step";
    i.continuous_collision = false;  // contacts found where the last step left the bodies
    i.contact_settings =
        "touching and overlapping pairs at the step start, resolved from the floor up "
        "(each against the body under it as immovable); Coulomb cone clamp, restitution of the "
        "step-start approach, the overlap pushed out in position; mu and e 0 unless set; a turned "
        "or turning box's impulse at the mean of its corners in the floor";
    i.friction_model = FrictionModel::cone;  // ResolveContact: |v_t| clamped by mu*j_n
    // The ideal law with the whole step-start depth pushed out in position, a touch a contact.
    i.bounce_law = {.erp = 1.0, .push_in_position = true, .touching = true};
    i.stack_law = {.sink_bound = 1e-12, .drift_bound = 1e-12, .still_bound = 1e-12};  // rigid
    i.turned_contact = TurnedContact::mean_corner;  // ResolvePointContact
    return i;
  }

  // A turned or turning box collides at its corners against the faces of unturned boxes below it
  // (ours/collision.hpp): with static boxes only, which are never turned.
  std::string cannot_run(const Scene& scene) const override {
    if (std::string why = Engine::cannot_run(scene); !why.empty()) return why;
    if (!scene.world.contacts) return {};
    for (const Body& b : scene.bodies)
      if (b.shape == Shape::box && b.is_static && !b.orientation.isApprox(Quat::Identity(), 0.0))
        return "a turned static box: ours collides axis-aligned static boxes";
    const auto turned = [](const Body& b) {
      return b.shape == Shape::box && !b.is_static &&
             (!b.orientation.isApprox(Quat::Identity(), 0.0) || !b.angular_velocity.isZero(0.0));
    };
    const auto dynamic = std::count_if(scene.bodies.begin(), scene.bodies.end(),
                                       [](const Body& b) { return !b.is_static; });
    const bool static_sphere =
        std::any_of(scene.bodies.begin(), scene.bodies.end(),
                    [](const Body& b) { return b.is_static && b.shape == Shape::sphere; });
    for (const Body& b : scene.bodies)
      if (turned(b) && (dynamic > 1 || static_sphere))
        return "a turned or turning box beside another dynamic body or a static sphere: ours "
               "collides a turned box only with static boxes (its corners against their faces)";
    return {};
  }

  void load(const Scene& scene, double h) override {
    h_ = static_cast<T>(h);
    world_.gravity = scene.world.gravity.cast<T>();
    world_.linearDrag = static_cast<T>(decay_per_step(scene, h));
    world_.angularDrag = static_cast<T>(angular_decay_per_step(scene, h));
    const Material material = scene_material(scene);
    world_.collisions = scene.world.contacts;
    world_.friction = static_cast<T>(material.friction.value_or(0.0));
    world_.restitution = static_cast<T>(material.restitution.value_or(0.0));
    models_.assign(scene.bodies.size(), {});
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      models_[i].translation = b.position.cast<T>();
      models_[i].rigidBody.velocity = b.velocity.cast<T>();
      models_[i].rigidBody.mass = static_cast<T>(b.mass);
      models_[i].rigidBody.isStatic = b.is_static;
      models_[i].rotation = b.orientation.cast<T>();
      models_[i].rigidBody.angularVelocity = b.angular_velocity.cast<T>();
      models_[i].rigidBody.inertia = inertia_of(b).cast<T>();
      ours::Collider<T>& c = models_[i].collider;
      c.shape = b.shape == Shape::sphere ? ours::Shape::Sphere : ours::Shape::Box;
      c.halfExtents = b.half_extents.cast<T>();
      c.radius = static_cast<T>(b.radius);
    }
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t i = 0; i < models_.size(); ++i)
      models_[i].rigidBody.force = forces[i].cast<T>();
  }

  void set_torques(std::span<const Vec3> torques) override {
    for (std::size_t i = 0; i < models_.size(); ++i)
      models_[i].rigidBody.torque = torques[i].cast<T>();
  }

  void step() override { ours::ApplyPhysics<T>(models_, world_, h_); }

  void read_rotation(std::span<RotationState> out) const override {
    (void)turn(RotationWriter<false>(out.data()));  // the check is read_rotation_append's business
  }

  // Like read_append: written once from the bodies' own numbers, checked in the same pass.
  bool read_rotation_append(std::size_t, RotationBuffer& out, StateUse use) const override {
    return append_rotations(out, models_.size(), use, [this](auto w) { return this->turn(w); });
  }

  // Seconds of `steps` calls of ours::ApplyPhysics alone (bare_step_loop in adapters.hpp).
  double bare_seconds(std::int64_t steps) {
    const auto start = std::chrono::steady_clock::now();
    for (std::int64_t n = 0; n < steps; ++n) ours::ApplyPhysics<T>(models_, world_, h_);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  void read(std::span<BodyState> out) const override {
    (void)write(StateWriter<false>(out.data()));  // the finite check is read_append's business
  }

  // Each state written once from the bodies' own numbers (exact: every float is a double) and
  // checked in the same pass; kept states streamed (StateWriter).
  bool read_append(std::size_t, StateBuffer& out, StateUse use) const override {
    return append_states(out, models_.size(), use, [this](auto w) { return this->write(w); });
  }

 private:
  // Puts every body's state in order into `w`; true when all are finite.
  template <typename Writer>
  bool write(Writer&& w) const {
    for (const ours::Model<T>& m : models_) {
      const ours::Vector3<T>& x = m.translation;
      const ours::Vector3<T>& v = m.rigidBody.velocity;
      w.put(x.x(), x.y(), x.z(), v.x(), v.y(), v.z());
    }
    return w.finish();
  }

  // Puts every body's rotational state in order into `w`; true when all are sound.
  template <typename Writer>
  bool turn(Writer&& w) const {
    for (const ours::Model<T>& m : models_) {
      const ours::Quaternion<T>& q = m.rotation;
      const ours::Vector3<T>& a = m.rigidBody.angularVelocity;
      w.put(q.w(), q.x(), q.y(), q.z(), a.x(), a.y(), a.z());
    }
    return w.finish();
  }

  T h_ = ours::PHYSICS_TIMESTEP<T>;
  ours::World<T> world_;
  std::vector<ours::Model<T>> models_;
};

// The bare loop of OursEngine<T> (bare_step_loop in adapters.hpp): load untimed, then steps only.
template <typename T>
double bare_seconds_of(const Scene& scene, double h) {
  OursEngine<T> e;
  e.load(scene, h);
  return e.bare_seconds(step_count(scene, h));
}

}  // namespace

std::unique_ptr<Engine> make_ours() {
  return std::make_unique<OursEngine<float>>();
}
std::unique_ptr<Engine> make_ours_f64() {
  return std::make_unique<OursEngine<double>>();
}

double bare_seconds_ours(const Scene& scene, double h) {
  return bare_seconds_of<float>(scene, h);
}
double bare_seconds_ours_f64(const Scene& scene, double h) {
  return bare_seconds_of<double>(scene, h);
}

}  // namespace dropcheck
