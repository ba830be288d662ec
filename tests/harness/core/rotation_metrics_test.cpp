// Tests harness/core/rotation_metrics.hpp: the geodesic angle against rotations built from a
// known axis and angle, its digits near zero, q = -q, and no 2*pi wrap; the momentum drift.
#include "harness/core/rotation_metrics.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

using namespace dropcheck;

TEST_CASE("the geodesic angle is the angle of the rotation between two orientations",
          "[rotation]") {
  const Quat a(Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()));
  for (double angle : {0.0, 1e-9, 0.3, 2.0, 3.1}) {
    const Quat b = a * Quat(Eigen::AngleAxisd(angle, Vec3(-1.0, 0.5, 0.2).normalized()));
    CHECK(geodesic_angle(a, b) == Approx(angle).epsilon(1e-12).margin(1e-15));
    CHECK(geodesic_angle(b, a) == Approx(angle).epsilon(1e-12).margin(1e-15));
  }
  // Near zero it keeps its digits: 1e-9 rad comes back as 0.99999999995e-9, where 2*acos(|a.b|)
  // gives 2.98e-8 (measured; acos near 1 has lost about half the digits).
  const Quat b = a * Quat(Eigen::AngleAxisd(1e-9, Vec3::UnitX()));
  CHECK(geodesic_angle(a, b) == Approx(1e-9).epsilon(1e-6));
  // q and -q are one orientation; a full turn is no turn (Euler-angle differences read 6.28 rad).
  const Quat minus(-a.w(), -a.x(), -a.y(), -a.z());
  CHECK(geodesic_angle(a, minus) == 0.0);
  const Quat full = a * Quat(Eigen::AngleAxisd(2.0 * M_PI, Vec3::UnitZ()));
  CHECK(geodesic_angle(a, full) < 1e-15);
}

TEST_CASE("the momentum drift is the largest departure from L(0), relative", "[rotation]") {
  CHECK(momentum_drift({Vec3(0, 0, 2), Vec3(0, 0.02, 2), Vec3(0, 0, 1.99)}) == Approx(0.01));
  CHECK(momentum_drift({Vec3::Zero(), Vec3(1, 0, 0)}) == 0.0);
  CHECK(momentum_drift({}) == 0.0);
}
