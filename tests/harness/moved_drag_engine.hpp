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
