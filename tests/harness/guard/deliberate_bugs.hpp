// Test doubles for the regression guard: a copy of ours' step (ours/physics.hpp, copied here so
// that these tests do not move when ours does) with one deliberate bug each, still declaring ours'
// law and arithmetic, exactly as an edited ours/physics.hpp behind the unchanged adapter would:
//   none                  v += g*h; v += (F/m)*h; v *= f; x += h*v     (the seed's step)
//   z_frozen              the same, then z and vz put back: motion along z lost
//   drag_twice            v *= f applied twice                         (inconsistent: order ~0)
//   gravity_half_step     v += g*h/2                                   (inconsistent)
//   explicit_euler        x += h*v_old, then the velocity update      (consistent: explicit Euler)
//   drag_after_position   v += ...; x += h*v; v *= f                   (consistent: ODE's order)
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "ours/physics.hpp"

namespace dropcheck::testing {

enum class Bug {
  none,
  z_frozen,
  drag_twice,
  gravity_half_step,
  explicit_euler,
  drag_after_position
};

template <typename T>
class BuggyOurs final : public Engine {
 public:
  explicit BuggyOurs(Bug bug) : bug_(bug) {}

  // ours' own declaration (adapters/ours.cpp), whatever the bug.
  EngineInfo info() const override {
    EngineInfo i;
    i.name = sizeof(T) == 4 ? "ours" : "ours-f64";
    i.scalar = sizeof(T) == 4 ? Scalar::f32 : Scalar::f64;
    i.law = DampingOrder::AfterForces;
    i.arithmetic = DampingForm::phi_multiply;
    return i;
  }

  void load(const Scene& scene, double h) override {
    h_ = static_cast<T>(h);
    gravity_ = scene.world.gravity.cast<T>();
    drag_ = static_cast<T>(decay_per_step(scene, h));
    bodies_.assign(scene.bodies.size(), {});
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
      bodies_[i] = {scene.bodies[i].position.cast<T>(), scene.bodies[i].velocity.cast<T>(),
                    ours::Vector3<T>::Zero(), static_cast<T>(scene.bodies[i].mass),
                    scene.bodies[i].is_static};
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t i = 0; i < bodies_.size(); ++i) bodies_[i].f = forces[i].cast<T>();
  }

  void step() override {
    for (Body& b : bodies_)
      if (!b.is_static) step_body(b);
  }

  void read(std::span<BodyState> out) const override {
    for (std::size_t i = 0; i < bodies_.size(); ++i)
      out[i] = {bodies_[i].x.template cast<double>(), bodies_[i].v.template cast<double>()};
  }

 private:
  struct Body {
    ours::Vector3<T> x, v, f;
    T m;
    bool is_static;
  };

  void step_body(Body& b) const {
    const ours::Vector3<T> x0 = b.x, v0 = b.v;
    b.v = b.v + gravity_ * (bug_ == Bug::gravity_half_step ? h_ / T(2) : h_);
    b.v = b.v + (b.f / b.m) * h_;
    if (bug_ != Bug::drag_after_position) b.v = b.v * drag_;
    if (bug_ == Bug::drag_twice) b.v = b.v * drag_;
    b.x = b.x + (bug_ == Bug::explicit_euler ? v0 : b.v) * h_;
    if (bug_ == Bug::drag_after_position) b.v = b.v * drag_;
    if (bug_ == Bug::z_frozen) b.x.z() = x0.z(), b.v.z() = v0.z();
  }

  Bug bug_;
  T h_ = T(1) / T(60), drag_ = T(1);
  ours::Vector3<T> gravity_ = ours::Vector3<T>::Zero();
  std::vector<Body> bodies_;
};

// A factory for ours (f32) with `bug`.
inline EngineFactory buggy_ours(Bug bug) {
  return [bug] { return std::make_unique<BuggyOurs<float>>(bug); };
}

// A factory for ours-f64 with `bug`.
inline EngineFactory buggy_ours_f64(Bug bug) {
  return [bug] { return std::make_unique<BuggyOurs<double>>(bug); };
}

}  // namespace dropcheck::testing
