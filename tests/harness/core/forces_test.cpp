// Tests harness/core/forces.cpp: the force laws every engine is handed, evaluated on a given state.
#include "harness/core/forces.hpp"

#include <catch2/catch.hpp>
#include <vector>

#include "harness/scene/scene_loader.hpp"
#include "tests/scene_texts.hpp"

namespace {

using dropcheck::Vec3;

// Three bodies: a static floor (0), "a" (1), "b" (2); `forces` is appended as [[force]] tables.
dropcheck::Scene with_forces(const std::string& forces) {
  using namespace dropcheck::testing;
  return dropcheck::parse_scene(scene_head("1.0", "", kEarth) +
                                    body_text("floor", kZero, "", "static = true\n") +
                                    body_text("a", kZero) + body_text("b", kZero) + forces,
                                "forces.toml");
}

std::vector<Vec3> forces_on(const dropcheck::Scene& s,
                            const std::vector<dropcheck::BodyState>& states) {
  std::vector<Vec3> out(states.size(), Vec3::Constant(99.0));  // garbage the call must clear
  dropcheck::compute_forces(s, states, out);
  return out;
}

}  // namespace

TEST_CASE("constant forces add up on their bodies and leave the others and static bodies at zero",
          "[forces]") {
  const dropcheck::Scene s = with_forces(R"(
[[force]]
constant = [2.0, 0.0, 0.0]
[[force]]
bodies = ["b"]
constant = [0.0, 1.0, -3.0]
)");
  const std::vector<Vec3> f = forces_on(s, std::vector<dropcheck::BodyState>(3));
  CHECK(f[0] == Vec3::Zero());
  CHECK(f[1] == Vec3(2.0, 0.0, 0.0));
  CHECK(f[2] == Vec3(2.0, 1.0, -3.0));
}

TEST_CASE("a spring with rest length 0 is F = -stiffness*(x - anchor) - damping*v", "[forces]") {
  const dropcheck::Scene s = with_forces(R"(
[[force]]
bodies = ["a"]
spring = { anchor = [0.0, 5.0, 0.0], stiffness = 400.0, damping = 2.0 }
)");
  std::vector<dropcheck::BodyState> st(3);
  st[1] = {Vec3(1.0, 3.0, -2.0), Vec3(0.5, -1.0, 0.25)};
  const std::vector<Vec3> f = forces_on(s, st);
  // d = (1, -2, -2): -400*d - 2*v = (-400 - 1, 800 + 2, 800 - 0.5)
  CHECK(f[1] == Vec3(-401.0, 802.0, 799.5));
  CHECK(f[2] == Vec3::Zero());
}

TEST_CASE("a spring with a rest length pulls along d/|d| by stiffness*(|d| - L)", "[forces]") {
  const dropcheck::Scene s = with_forces(R"(
[[force]]
bodies = ["a", "b"]
spring = { anchor = [0.0, 0.0, 0.0], stiffness = 10.0, rest_length = 2.0 }
)");
  std::vector<dropcheck::BodyState> st(3);
  st[1].position = {0.0, 2.0, 0.0};  // at rest length: no force
  st[2].position = {3.0, 4.0, 0.0};  // |d| = 5: F = -10*3*(0.6, 0.8, 0)
  const std::vector<Vec3> f = forces_on(s, st);
  CHECK(f[1] == Vec3::Zero());
  CHECK(f[2].isApprox(Vec3(-18.0, -24.0, 0.0), 1e-15));  // measured 0 (exact)
}

TEST_CASE("a body sitting on the anchor of a spring with a rest length gets no NaN", "[forces]") {
  const dropcheck::Scene s = with_forces(R"(
[[force]]
bodies = ["a"]
spring = { anchor = [0.0, 0.0, 0.0], stiffness = 10.0, damping = 1.0, rest_length = 1.0 }
)");
  std::vector<dropcheck::BodyState> st(3);
  st[1].velocity = {0.0, 2.0, 0.0};
  const std::vector<Vec3> f = forces_on(s, st);
  CHECK(f[1] == Vec3(0.0, -2.0, 0.0));  // direction undefined: only the dashpot acts
}
