// A test double for the stability tests (tests/harness/judge/stability_*_test.cpp,
// tests/harness/study/stability_*_test.cpp): a semi-implicit Euler engine like ours that places
// failures where the real engines do not have them, and the helpers those tests share.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/registry.hpp"
#include "harness/core/scene.hpp"
#include "harness/judge/stability_classify.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"

namespace dropcheck::testing {

// scenarios/extreme/<stem>.toml, loaded.
inline Scene extreme_scene(const std::string& stem) {
  return load_scene(std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/extreme/" + stem + ".toml");
}

// True when the engine `name` is compiled in.
inline bool engine_available(const std::string& name) {
  return make_engine(name) != nullptr;
}

// A factory for the registry's engine `name`.
inline EngineFactory registry_factory(const std::string& name) {
  return [name] { return make_engine(name); };
}

// A semi-implicit Euler engine like ours (v = phi*(v + (g + F/m)*h); x += h*v; static bodies stay)
// that claims contacts but has none, and injects one fault from step `at` on.
class FaultyEngine final : public Engine {
 public:
  enum class Fault { none, nan, error, clamp, stop, double_speed };
  FaultyEngine(Fault fault, std::int64_t at) : fault_(fault), at_(at) {}

  EngineInfo info() const override {
    EngineInfo i;
    i.name = "faulty";
    i.capabilities.contacts = true;
    return i;
  }
  void load(const Scene& scene, double h) override {
    scene_ = scene;
    h_ = h;
    n_ = 0;
    states_.clear();
    for (const Body& b : scene.bodies) states_.push_back({b.position, b.velocity});
  }
  void set_forces(std::span<const Vec3> f) override { forces_.assign(f.begin(), f.end()); }
  void step() override {
    if (++n_ >= at_ && fault_ == Fault::error) throw EngineError("solver gave up");
    for (std::size_t i = 0; i < states_.size(); ++i) {
      if (scene_.bodies[i].is_static) continue;
      BodyState& s = states_[i];
      s.velocity = decay_per_step(scene_, h_) *
                   (s.velocity + (scene_.world.gravity + forces_[i] / scene_.bodies[i].mass) * h_);
      if (n_ >= at_ && fault_ == Fault::stop) s.velocity.setZero();  // "sleeping"
      if (n_ >= at_ && fault_ == Fault::double_speed) s.velocity *= 2.0;
      if (n_ >= at_ && fault_ == Fault::nan)
        s.velocity.x() = std::numeric_limits<double>::quiet_NaN();
      s.position += h_ * s.velocity;
    }
  }
  void read(std::span<BodyState> out) const override {
    std::copy(states_.begin(), states_.end(), out.begin());
  }
  bool speed_clamped() const override { return fault_ == Fault::clamp && n_ >= at_; }

 private:
  Fault fault_;
  std::int64_t at_;
  Scene scene_;
  double h_ = 0.0;
  std::int64_t n_ = 0;
  std::vector<BodyState> states_;
  std::vector<Vec3> forces_;
};

// `scene` run at its own step on a FaultyEngine with `fault` from step `at` on, classified in f64.
inline Verdict classify_faulty(const Scene& scene, FaultyEngine::Fault fault, std::int64_t at) {
  FaultyEngine engine(fault, at);
  return classify_run(scene, run_scene(engine, scene, scene.timestep.seconds), Scalar::f64);
}

}  // namespace dropcheck::testing
