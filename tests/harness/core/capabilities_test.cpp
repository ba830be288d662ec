// Tests to_string(Capabilities) (harness/core/engine.hpp): the one text `dropcheck engines` and the
// report's engine table print for what an engine can run.
#include <catch2/catch.hpp>

#include "harness/core/engine.hpp"

using dropcheck::Capabilities;
using dropcheck::Rotation;

TEST_CASE("an engine's capabilities read as free flight plus what it adds", "[engine]") {
  CHECK(to_string(Capabilities{}) == "free flight");
  CHECK(to_string(Capabilities{.contacts = true, .rotation = Rotation::full}) ==
        "free flight, contacts, 3-D rotation");
  CHECK(to_string(Capabilities{.planar_only = true, .rotation = Rotation::spin_z}) ==
        "free flight, 2-D (x-y plane), turns about z");
}

namespace {

// An engine that declares `caps` and does nothing else: only Engine::cannot_run is exercised.
class Declares final : public dropcheck::Engine {
 public:
  explicit Declares(Capabilities caps) : caps_(caps) {}
  dropcheck::EngineInfo info() const override {
    dropcheck::EngineInfo i;
    i.capabilities = caps_;
    return i;
  }
  void load(const dropcheck::Scene&, double) override {}
  void set_forces(std::span<const dropcheck::Vec3>) override {}
  void step() override {}
  void read(std::span<dropcheck::BodyState>) const override {}

 private:
  Capabilities caps_;
};

}  // namespace

TEST_CASE("a scene with a material or a sphere runs only where the adapter maps it",
          "[engine][contact]") {
  dropcheck::Scene scene;
  scene.world.contacts = true;
  scene.bodies.resize(1);
  const Declares boxes_only(Capabilities{.contacts = true});
  CHECK(boxes_only.cannot_run(scene).empty());
  scene.bodies[0].friction = 0.5;
  CHECK(boxes_only.cannot_run(scene) == "friction: this engine's adapter does not map it");
  const Declares mapped(Capabilities{.contacts = true, .friction = true, .spheres = true});
  CHECK(mapped.cannot_run(scene).empty());
  scene.bodies[0].restitution = 0.5;
  CHECK(mapped.cannot_run(scene) == "restitution: this engine's adapter does not map it");
  scene.bodies[0].restitution.reset();
  scene.bodies[0].shape = dropcheck::Shape::sphere;
  scene.bodies[0].radius = 0.5;
  CHECK(boxes_only.cannot_run(scene) == "spheres: this engine's adapter builds boxes only");
  CHECK(mapped.cannot_run(scene).empty());
  CHECK(to_string(Capabilities{
            .contacts = true, .friction = true, .restitution = true, .spheres = true}) ==
        "free flight, contacts, friction, restitution, spheres");
}
