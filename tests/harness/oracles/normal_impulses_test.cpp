// Tests harness/oracles/normal_impulses.cpp on hand-made runs whose impulses are known: a free fall
// has none, an ideal bounce one step of (1 + e)*v, and a pull or a push from a distance shows
// where it happens.
#include "harness/oracles/normal_impulses.hpp"

#include <catch2/catch.hpp>
#include <vector>

using namespace dropcheck;

namespace {

constexpr double kStep = 0.01, kG = 10.0, kRadius = 0.5, kDouble = 2.2e-16;

// A ball of radius 0.5 on a floor whose top is y = 0: states from (y, vy) pairs.
std::vector<BodyState> ball(const std::vector<std::pair<double, double>>& yv) {
  std::vector<BodyState> out;
  for (const auto& [y, v] : yv) out.push_back({Vec3(0.0, y, 0.0), Vec3(0.0, v, 0.0)});
  return out;
}

}  // namespace

TEST_CASE("a free fall has no normal impulse; an ideal bounce has one, at its restitution",
          "[impulses]") {
  // Semi-implicit Euler from y = 0.56 at rest: v = -0.1, -0.2, -0.3 and y -= h*v, 0.054 m above
  // the floor; then a contact step that ends on the floor going up at 0.5 of the 0.4 m/s the fall
  // would have reached.
  const std::vector<BodyState> s = ball({{0.56, 0.0},
                                         {0.559, -0.1},
                                         {0.557, -0.2},
                                         {0.554, -0.3},
                                         {0.5, 0.2},  // on the floor, going up at 0.5 * 0.4
                                         {0.502, 0.1}});
  const NormalCertificate c = normal_certificate(s, kRadius, 0.0, kG, kStep, kDouble);
  CHECK(c.contact_steps == 1);
  CHECK(c.pull_step < 0);
  CHECK(c.widest_gap == 0.0);  // it touched the floor in that step
  CHECK(c.deepest == 0.0);
  CHECK(c.rebound == Approx(0.5));
  CHECK(c.rebound_step == 4);
}

TEST_CASE("a pull, a push from a gap and an overlap are named with their steps", "[impulses]") {
  const std::vector<BodyState> s = ball({{0.6, 0.0},
                                         {0.599, -0.1},
                                         {0.597, -0.25},  // 0.05 m/s more down than gravity: a pull
                                         {0.5975, 0.05},  // pushed up 0.0975 above the floor
                                         {0.49, -0.05},   // 1 cm into the floor
                                         {0.5, 0.0}});
  const NormalCertificate c = normal_certificate(s, kRadius, 0.0, kG, kStep, kDouble);
  CHECK(c.pull_step == 2);
  CHECK(c.worst_pull == Approx(-0.5));   // -0.05 m/s against g*h = 0.1
  CHECK(c.widest_gap == Approx(0.097));  // the smaller of the gaps before and after step 3
  CHECK(c.widest_gap_step == 3);
  CHECK(c.deepest == Approx(0.01));
  CHECK(c.deepest_step == 4);
}

TEST_CASE("float rounding is neither a push nor a pull", "[impulses]") {
  // A float engine's fall: each speed rounded to float, 1.2e-7 relative.
  std::vector<std::pair<double, double>> yv{{10.0, 0.0}};
  for (int n = 1; n <= 50; ++n) {
    const double v = static_cast<double>(static_cast<float>(-kG * kStep * n));
    yv.push_back({yv.back().first + kStep * v, v});
  }
  const NormalCertificate c = normal_certificate(ball(yv), kRadius, 0.0, kG, kStep, 1.2e-7);
  CHECK(c.contact_steps == 0);
  CHECK(c.pull_step < 0);
}
