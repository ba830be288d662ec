// Tests harness/core/rotation_law.hpp's advance_rotation where the linear member places the turn:
// with the semi-implicit position update the orientation turns by the new w, with the explicit one
// (Chipmunk) by the step-start w, before the torque and the damping change it.
#include "harness/core/rotation_law.hpp"

#include <catch2/catch.hpp>
#include <cmath>

namespace {

using dropcheck::DampingOrder;
using dropcheck::Gyroscopic;
using dropcheck::Law;
using dropcheck::OrientationUpdate;
using dropcheck::PositionUpdate;
using dropcheck::RotationLaw;
using dropcheck::Spin;
using V = Eigen::Vector3d;

// One step of h = 0.1 with phi_a = 0.5 on a body of unit moments (no gyroscopic term) spinning at
// 2 rad/s about z under a torque of 1 N m about z; returns the spin after it.
Spin<double> one_step(Law linear) {
  Spin<double> s;
  s.w = V(0, 0, 2);
  dropcheck::advance_rotation<double>({Gyroscopic::none, OrientationUpdate::exponential_map},
                                      linear, 0.5, 0.1, V(1, 1, 1), V(0, 0, 1), s);
  return s;
}

double angle_about_z(const Spin<double>& s) {
  return 2.0 * std::atan2(s.q.z(), s.q.w());
}

}  // namespace

TEST_CASE("the explicit placement turns by the step-start w, the semi-implicit by the new w",
          "[rotation][law]") {
  // w1 = 0.5*2 + 0.1*1 = 1.1 either way (damping before the forces).
  const Spin<double> semi = one_step(DampingOrder::BeforeForces);
  const Spin<double> expl = one_step({DampingOrder::BeforeForces, PositionUpdate::Explicit});
  CHECK(semi.w.z() == Approx(1.1).epsilon(1e-15));
  CHECK(expl.w.z() == Approx(1.1).epsilon(1e-15));
  CHECK(angle_about_z(semi) == Approx(0.11).epsilon(1e-14));  // h*w1
  CHECK(angle_about_z(expl) == Approx(0.2).epsilon(1e-14));   // h*w0
  // Damping after the forces: w1 = 0.5*(2 + 0.1) = 1.05, the turn still by w0 when explicit.
  const Spin<double> after = one_step({DampingOrder::AfterForces, PositionUpdate::Explicit});
  CHECK(after.w.z() == Approx(1.05).epsilon(1e-15));
  CHECK(angle_about_z(after) == Approx(0.2).epsilon(1e-14));
}
