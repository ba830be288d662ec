// A free-flight engine double for the run-loop tests: every body starts at its scene state and
// moves by x += h*v, then v += h*F (unit mass, no gravity), F being the forces last handed over
// (zero until then). A test derives from it and places its failures through the hooks.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/scene.hpp"

namespace dropcheck::testing {

// The double itself; the hooks do nothing unless a derived double overrides them.
class FakeEngine : public Engine {
 public:
  // A double that calls itself `name` in its info().
  explicit FakeEngine(std::string name) : name_(std::move(name)) {}

  // Only the name is set; the rest is EngineInfo's default.
  EngineInfo info() const override {
    EngineInfo i;
    i.name = name_;
    return i;
  }
  // Takes every body's initial state and zero forces, then calls on_load().
  void load(const Scene& scene, double h) override {
    h_ = h;
    step_ = 0;
    states_.clear();
    for (const Body& b : scene.bodies) states_.push_back({b.position, b.velocity});
    forces_.assign(scene.bodies.size(), Vec3::Zero());
    on_load();
  }
  // Keeps the forces for the next step, then calls on_forces() with them.
  void set_forces(std::span<const Vec3> f) override {
    forces_.assign(f.begin(), f.end());
    on_forces(forces_);
  }
  // Counts the step, calls before_move(), moves every body, then calls after_move().
  void step() override {
    ++step_;
    before_move(step_);
    for (std::size_t i = 0; i < states_.size(); ++i) {
      states_[i].position += h_ * states_[i].velocity;
      states_[i].velocity += h_ * forces_[i];
    }
    after_move(step_);
  }
  // The states after the last step, indexed like Scene::bodies.
  void read(std::span<BodyState> out) const override {
    std::copy(states_.begin(), states_.end(), out.begin());
  }

 protected:
  // Called at the end of load(), the states already set.
  virtual void on_load() {}
  // Called by set_forces() with the forces just handed over.
  virtual void on_forces(const std::vector<Vec3>&) {}
  // Called by step() with the number of the step (1 for the first) before anything moves.
  virtual void before_move(std::int64_t) {}
  // Called by step() with the number of the step once every body has moved.
  virtual void after_move(std::int64_t) {}
  // How many steps were taken since the last load().
  std::int64_t steps_taken() const { return step_; }
  // Each body's state, indexed like Scene::bodies; a hook may overwrite it.
  std::vector<BodyState> states_;

 private:
  std::string name_;
  double h_ = 0.0;
  std::int64_t step_ = 0;
  std::vector<Vec3> forces_;
};

}  // namespace dropcheck::testing
