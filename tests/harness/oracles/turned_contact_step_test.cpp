// Tests harness/oracles/turned_contact_step.cpp against the closed form of an edge landing
// (tests/ours/edge_landing.hpp): one impulse at the edge's midpoint stops it; and a corner within
// rounding of the face is tried both ways.
#include "harness/oracles/turned_contact_step.hpp"

#include <catch2/catch.hpp>

#include "harness/scene/scene_loader.hpp"
#include "tests/ours/edge_landing.hpp"
#include "tests/scene_texts.hpp"

using namespace dropcheck;
using namespace dropcheck::testing;

namespace {

Scene edge_scene() {
  return parse_scene(scene_head("1.0", "1/60", kEarth, "contacts = true\n") +
                         body_text("floor", "[0.0, -0.5, 0.0]", "",
                                   "static = true\nhalf_extents = [10.0, 0.5, 10.0]\n") +
                         body_text("cube", "[0.0, 2.0, 0.0]"),
                     "edge.toml");
}

EngineInfo ours_members() {
  EngineInfo i;
  i.law = DampingOrder::AfterForces;
  i.rotation_law = {Gyroscopic::explicit_term, OrientationUpdate::first_order};
  i.turned_contact = TurnedContact::mean_corner;
  return i;
}

}  // namespace

TEST_CASE("an edge landing: the law's step is the closed form of one impulse at the edge",
          "[contact][turned]") {
  const EdgeLanding e;
  const Scene scene = edge_scene();
  const TurnedContactScope scope = turned_contact_scope(scene, ours_members(), e.h);
  REQUIRE(scope.not_judged.empty());
  const std::vector<BodyState> linear = {{scene.bodies[0].position, Vec3::Zero()},
                                         {e.centre(), Vec3(0.0, e.v0, 0.0)}};
  const std::vector<RotationState> rotation = {{}, {e.rotation(), Vec3::Zero()}};
  const std::vector<TurnedCandidate> next =
      turned_contact_step(scope.setup, linear, rotation, 1e-12);
  REQUIRE(next.size() == 1);
  CHECK(next[0].contacts == 2);  // the edge's two corners
  const Vec3 v = next[0].linear[1].velocity;
  const Vec3 w = next[0].rotation[1].angular_velocity;
  CHECK(v.y() == Approx(e.vy()).epsilon(1e-14));
  CHECK(w.z() == Approx(e.wz()).epsilon(1e-14));
  CHECK(std::abs(v.x()) + std::abs(v.z()) + std::abs(w.x()) + std::abs(w.y()) < 1e-15);
  // The depth is pushed out: the centre moves h*v_y and up by the 1e-4 m it started in.
  CHECK(next[0].linear[1].position.y() ==
        Approx(e.centre().y() + e.h * e.vy() + e.depth).epsilon(1e-14));
}

TEST_CASE("a corner within rounding of the face is tried both ways; one far above is not",
          "[contact][turned]") {
  const EdgeLanding e;
  const Scene scene = edge_scene();
  const TurnedContactScope scope = turned_contact_scope(scene, ours_members(), e.h);
  const Vec3 resting = e.centre() + Vec3(0.0, e.depth + 1e-13, 0.0);  // the edge 1e-13 m above
  const std::vector<BodyState> linear = {{scene.bodies[0].position, Vec3::Zero()},
                                         {resting, Vec3::Zero()}};
  const std::vector<RotationState> rotation = {{}, {e.rotation(), Vec3::Zero()}};
  const std::vector<TurnedCandidate> both =
      turned_contact_step(scope.setup, linear, rotation, 1e-12);
  REQUIRE(both.size() == 4);  // two corners, each in contact or not
  CHECK(both[0].contacts == 0);
  CHECK(both[3].contacts == 2);
  const std::vector<TurnedCandidate> one =
      turned_contact_step(scope.setup, linear, rotation, 1e-14);
  REQUIRE(one.size() == 1);
  CHECK(one[0].contacts == 0);  // 1e-13 m above: free
}

TEST_CASE("the law applies to one dynamic box over static boxes, damped after the forces",
          "[contact][turned]") {
  const EdgeLanding e;
  const Scene scene = edge_scene();
  EngineInfo before = ours_members();
  before.law = DampingOrder::BeforeForces;
  CHECK_THAT(turned_contact_scope(scene, before, e.h).not_judged,
             Catch::Contains("not after the forces"));
  Scene two = scene;
  two.bodies.push_back(scene.bodies[1]);
  CHECK_THAT(turned_contact_scope(two, ours_members(), e.h).not_judged,
             Catch::Contains("not one dynamic box"));
}
