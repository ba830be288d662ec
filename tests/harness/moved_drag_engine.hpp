// A test double for the regression guard: ours' own structures (ours::Model, ours::World,
// ours::ApplyGravity) with one deliberate change, the drag moved after the position update:
//   ours:   v = f*(v + a*h);  x += h*v          (the seed's order, DampingOrder::AfterForces)
//   double: v += a*h;  x += h*v;  v *= f        (ODE's order, DampingOrder::AfterPosition)
// It still declares ours' name and law, as an edited ours/physics.hpp would, so that the oracle
// checks and the baselines see exactly what a careless change to the integrator looks like.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "harness/engine.hpp"
#include "ours/physics.hpp"

namespace dropcheck::testing {

template <typename T>
class MovedDragEngine final : public Engine {
 public:
  EngineInfo info() const override {
    EngineInfo i;
    i.name = sizeof(T) == 4 ? "ours" : "ours-f64";
    i.scalar = sizeof(T) == 4 ? Scalar::f32 : Scalar::f64;
    i.law = DampingOrder::AfterForces;  // what ours declares; the double no longer follows it
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
    for (std::size_t i = 0; i < models_.size(); ++i) models_[i].rigidBody.force = forces[i].cast<T>();
  }

  // ApplyPhysics with IntegrateLinearForce's drag moved after the position update.
  void step() override {
    for (ours::Model<T>& m : models_) {
      if (m.rigidBody.isStatic) continue;
      ours::ApplyGravity(&m, world_, h_);
      m.rigidBody.velocity += (m.rigidBody.force / m.rigidBody.mass) * h_;
      m.rigidBody.force = ours::Vector3<T>::Zero();
      m.translation += m.rigidBody.velocity * h_;
      m.rigidBody.velocity *= world_.linearDrag;
    }
  }

  void read(std::span<BodyState> out) const override {
    for (std::size_t i = 0; i < models_.size(); ++i) {
      out[i].position = models_[i].translation.template cast<double>();
      out[i].velocity = models_[i].rigidBody.velocity.template cast<double>();
    }
  }

 private:
  T h_ = T(1) / T(60);
  ours::World<T> world_;
  std::vector<ours::Model<T>> models_;
};

// Factories for make_baseline, bless and check_determinism.
inline std::unique_ptr<Engine> make_moved_drag_f64() { return std::make_unique<MovedDragEngine<double>>(); }
inline std::unique_ptr<Engine> make_moved_drag_f32() { return std::make_unique<MovedDragEngine<float>>(); }

}  // namespace dropcheck::testing
