// Test doubles for the regression guard on contact scenes: ours' contact step (ours/collision.hpp)
// with one deliberate bug each, still declaring ours' contact laws, as an edited
// ours/physics.hpp behind the unchanged adapter would:
//   none                      the step of ours/physics.hpp (ApplyPhysicsWithCollisions)
//   friction_after_position   the positions move before the contacts are resolved
//   restitution_twice         the rebound's impulse applied twice (2e of the approach)
//   grip_whole_gravity        the friction bounded by mu*m*|g| on an incline, not mu*m*g*cos(theta)
//                             (its coefficient scaled by |g|/g_n: the normal force ignores the
//                             incline)
//   turned_through_centre     a turned box's impulse through its centre (its arm forgotten)
//   turned_before_contact     the orientation turned by the angular velocity before the contacts
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/registry.hpp"
#include "ours/physics.hpp"

namespace dropcheck::testing {

enum class ContactBug {
  none,
  friction_after_position,
  restitution_twice,
  grip_whole_gravity,
  turned_through_centre,
  turned_before_contact,
};

class BuggyContactOurs final : public Engine {
 public:
  explicit BuggyContactOurs(ContactBug bug) : bug_(bug) {}

  // ours-f64's own declaration (its adapter's), whatever the bug.
  EngineInfo info() const override { return make_engine("ours-f64")->info(); }

  void load(const Scene& scene, double h) override {
    h_ = h;
    world_.gravity = scene.world.gravity;
    world_.linearDrag = decay_per_step(scene, h);
    world_.angularDrag = angular_decay_per_step(scene, h);
    world_.collisions = scene.world.contacts;
    world_.friction = scene_material(scene).friction.value_or(0.0);
    if (bug_ == ContactBug::grip_whole_gravity)
      world_.friction *= scene.world.gravity.norm() / std::abs(scene.world.gravity.y());
    world_.restitution = scene_material(scene).restitution.value_or(0.0);
    models_.assign(scene.bodies.size(), ours::Model<double>{});
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      models_[i].translation = b.position;
      models_[i].rigidBody.velocity = b.velocity;
      models_[i].rigidBody.mass = b.mass;
      models_[i].rigidBody.isStatic = b.is_static;
      models_[i].rotation = b.orientation;
      models_[i].rigidBody.angularVelocity = b.angular_velocity;
      models_[i].rigidBody.inertia = inertia_of(b);
      models_[i].collider.shape = b.shape == Shape::sphere ? ours::Shape::Sphere : ours::Shape::Box;
      models_[i].collider.halfExtents = b.half_extents;
      models_[i].collider.radius = b.radius;
    }
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t i = 0; i < models_.size(); ++i) models_[i].rigidBody.force = forces[i];
  }

  void step() override {
    std::span<ours::Model<double>> m(models_);
    std::vector<ours::Contact<double>> contacts =
        ours::FindContacts<double>(std::span<const ours::Model<double>>(m));
    if (bug_ == ContactBug::turned_through_centre)
      for (ours::Contact<double>& c : contacts) c.atPoint = false;
    std::vector<char> turns(m.size(), 0);
    for (std::size_t i = 0; i < m.size(); ++i)
      if (!m[i].rigidBody.isStatic) {
        ours::ApplyGravity(&m[i], world_, h_);
        ours::IntegrateLinearVelocity(&m[i], world_, h_);
        turns[i] = ours::Turns(m[i]);
        if (turns[i]) ours::IntegrateAngularVelocity(&m[i], world_, h_);
      }
    if (bug_ == ContactBug::friction_after_position) move(m);
    if (bug_ == ContactBug::turned_before_contact) turn(m, turns);
    const double e = world_.restitution;
    ours::ResolveContacts(m, contacts, world_.friction, e);
    if (bug_ == ContactBug::restitution_twice)  // the rebound's impulse once more
      for (const ours::Contact<double>& c : contacts)
        if (c.approach > 0.0) m[c.body].rigidBody.velocity += e * c.approach * c.normal;
    if (bug_ != ContactBug::friction_after_position) move(m);
    if (bug_ != ContactBug::turned_before_contact) turn(m, turns);
    ours::PushOut(m, contacts);
  }

  void read(std::span<BodyState> out) const override {
    for (std::size_t i = 0; i < models_.size(); ++i)
      out[i] = {models_[i].translation, models_[i].rigidBody.velocity};
  }

  void read_rotation(std::span<RotationState> out) const override {
    for (std::size_t i = 0; i < models_.size(); ++i)
      out[i] = {models_[i].rotation, models_[i].rigidBody.angularVelocity};
  }

 private:
  void move(std::span<ours::Model<double>> m) const {
    for (ours::Model<double>& model : m)
      if (!model.rigidBody.isStatic) ours::IntegratePosition(&model, h_);
  }

  void turn(std::span<ours::Model<double>> m, const std::vector<char>& turns) const {
    for (std::size_t i = 0; i < m.size(); ++i)
      if (!m[i].rigidBody.isStatic && (turns[i] || !m[i].rigidBody.angularVelocity.isZero(0.0)))
        ours::IntegrateRotation(&m[i], h_);
  }

  ContactBug bug_;
  double h_ = 1.0 / 60.0;
  ours::World<double> world_;
  std::vector<ours::Model<double>> models_;
};

inline EngineFactory buggy_contact_ours(ContactBug bug) {
  return [bug] { return std::make_unique<BuggyContactOurs>(bug); };
}

}  // namespace dropcheck::testing
