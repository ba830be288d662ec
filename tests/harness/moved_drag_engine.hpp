// Test doubles for the regression guard: ours' own structures (ours::Model, ours::World,
// ours::ApplyGravity) stepped with the drag on either side of the position update:
//   DampingOrder::AfterForces    v += a*h;  v *= f;  x += h*v   (the seed's order,
//   IntegrateLinearForce) DampingOrder::AfterPosition  v += a*h;  x += h*v;  v *= f   (the drag
//   moved after the position)
// Each double runs one order and declares a law, possibly another one, exactly as an edited
// ours/physics.hpp whose adapter still declares the old law would. The orders are written here, not
// taken from ours/physics.hpp, so that these tests do not move when ours does.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "ours/physics.hpp"

namespace dropcheck::testing {

template <typename T>
class ReorderedDragEngine final : public Engine {
 public:
  // Runs `runs` (AfterForces or AfterPosition) and tells the harness it follows `declares`.
  ReorderedDragEngine(DampingOrder runs, DampingOrder declares)
      : runs_(runs), declares_(declares) {}

  EngineInfo info() const override {
    EngineInfo i;
    i.name = sizeof(T) == 4 ? "ours" : "ours-f64";
    i.scalar = sizeof(T) == 4 ? Scalar::f32 : Scalar::f64;
    i.law = declares_;
    return i;
  }

  void load(const Scene& scene, double h) override {
    h_ = static_cast<T>(h);
    world_.gravity = scene.world.gravity.cast<T>();
    world_.linearDrag = static_cast<T>(decay_per_step(scene, h));
    models_.assign(scene.bodies.size(), {});
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      models_[i].translation = scene.bodies[i].position.cast<T>();
      models_[i].rigidBody.velocity = scene.bodies[i].velocity.cast<T>();
      models_[i].rigidBody.mass = static_cast<T>(scene.bodies[i].mass);
      models_[i].rigidBody.isStatic = scene.bodies[i].is_static;
    }
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t i = 0; i < models_.size(); ++i)
      models_[i].rigidBody.force = forces[i].cast<T>();
  }

  // ApplyPhysics with IntegrateLinearForce's drag where `runs` puts it.
  void step() override {
    for (ours::Model<T>& m : models_) {
      if (m.rigidBody.isStatic) continue;
      ours::ApplyGravity(&m, world_, h_);
      ours::RigidBody<T>& body = m.rigidBody;
      body.velocity += (body.force / body.mass) * h_;
      body.force = ours::Vector3<T>::Zero();
      if (runs_ == DampingOrder::AfterForces) body.velocity *= world_.linearDrag;
      m.translation += body.velocity * h_;
      if (runs_ == DampingOrder::AfterPosition) body.velocity *= world_.linearDrag;
    }
  }

  void read(std::span<BodyState> out) const override {
    for (std::size_t i = 0; i < models_.size(); ++i) {
      out[i].position = models_[i].translation.template cast<double>();
      out[i].velocity = models_[i].rigidBody.velocity.template cast<double>();
    }
  }

 private:
  DampingOrder runs_, declares_;
  T h_ = T(1) / T(60);
  ours::World<T> world_;
  std::vector<ours::Model<T>> models_;
};

// The seed's order, declared honestly: what ours-f64 is today.
inline std::unique_ptr<Engine> make_seed_order_f64() {
  return std::make_unique<ReorderedDragEngine<double>>(DampingOrder::AfterForces,
                                                       DampingOrder::AfterForces);
}

// The careless change: drag moved after the position update, the seed's law still declared.
inline std::unique_ptr<Engine> make_moved_drag_f64() {
  return std::make_unique<ReorderedDragEngine<double>>(DampingOrder::AfterPosition,
                                                       DampingOrder::AfterForces);
}

}  // namespace dropcheck::testing

namespace dropcheck::testing {

// ours-f64 with its quaternion update changed: the exact rotation by w*h (the exponential map)
// instead of ours's first-order q + (h/2)*(0, w)*q, while still declaring ours's rotational member
// (explicit/first-order), as an edited IntegrateAngularForce whose adapter was not updated would.
// Everything else as ours: ApplyGravity, IntegrateLinearForce, the explicit gyroscopic term.
class ExpMapOursEngine final : public Engine {
 public:
  EngineInfo info() const override {
    EngineInfo i;
    i.name = "ours-f64";
    i.scalar = Scalar::f64;
    i.law = DampingOrder::AfterForces;
    i.arithmetic = DampingForm::phi_multiply;
    i.capabilities.rotation = Rotation::full;
    i.rotation_law = {Gyroscopic::explicit_term, OrientationUpdate::first_order};
    return i;
  }

  void load(const Scene& scene, double h) override {
    h_ = h;
    world_.gravity = scene.world.gravity;
    world_.linearDrag = decay_per_step(scene, h);
    world_.angularDrag = angular_decay_per_step(scene, h);
    models_.assign(scene.bodies.size(), {});
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      models_[i].translation = b.position;
      models_[i].rotation = b.orientation;
      models_[i].rigidBody.velocity = b.velocity;
      models_[i].rigidBody.angularVelocity = b.angular_velocity;
      models_[i].rigidBody.inertia = inertia_of(b);
      models_[i].rigidBody.mass = b.mass;
      models_[i].rigidBody.isStatic = b.is_static;
    }
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t i = 0; i < models_.size(); ++i) models_[i].rigidBody.force = forces[i];
  }
  void set_torques(std::span<const Vec3> torques) override {
    for (std::size_t i = 0; i < models_.size(); ++i) models_[i].rigidBody.torque = torques[i];
  }

  void step() override {
    for (ours::Model<double>& m : models_) {
      if (m.rigidBody.isStatic) continue;
      ours::ApplyGravity(&m, world_, h_);
      ours::IntegrateLinearForce(&m, world_, h_);
      ours::RigidBody<double>& body = m.rigidBody;
      Vec3& w = body.angularVelocity;
      const Eigen::Matrix3d R = m.rotation.toRotationMatrix();
      const Vec3 momentum = R * body.inertia.cwiseProduct(R.transpose() * w);
      w += R * (R.transpose() * (body.torque - w.cross(momentum))).cwiseQuotient(body.inertia) * h_;
      body.torque.setZero();
      w *= world_.angularDrag;
      if (w.norm() > 0.0)  // the exponential map: the exact turn by |w|*h about w
        m.rotation =
            (Quat(Eigen::AngleAxisd(w.norm() * h_, w.normalized())) * m.rotation).normalized();
    }
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
  double h_ = 1.0 / 60.0;
  ours::World<double> world_;
  std::vector<ours::Model<double>> models_;
};

}  // namespace dropcheck::testing
