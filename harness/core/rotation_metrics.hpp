// Metrics of rotation that do not lie: how far apart two orientations are, as one angle that keeps
// its digits near zero and does not wrap, and how far the angular momentum drifted.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "harness/core/scene.hpp"

namespace dropcheck {

using Quat = Eigen::Quaterniond;

// The angle (rad, in [0, pi]) of the rotation taking orientation `a` to `b`: with d = a* b,
//   angle = 2*atan2(|vec(d)|, |w(d)|).
// atan2 of the vector part keeps full relative precision for tiny angles, where 2*acos(|a.b|)
// loses half its digits (acos near 1); |w| makes q and -q, the same orientation, 0 apart; and a
// turn through 2*pi is 0, never the 6.28 rad that subtracting Euler angles gives. Unit
// quaternions expected; their norms cancel in the ratio.
inline double geodesic_angle(const Quat& a, const Quat& b) {
  const Quat d = a.conjugate() * b;
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

// The world angular momentum I_w*w = R*(I .* (R^T*w)) of a body of principal moments `inertia`
// (body frame) turned by `q` and spinning at the world angular velocity `w`.
inline Vec3 world_momentum(const Quat& q, const Vec3& w, const Vec3& inertia) {
  return q * inertia.cwiseProduct(q.conjugate() * w);
}

// max over samples of |L(t) - L(0)| / |L(0)|, L the world angular momentum; 0 for L(0) = 0.
inline double momentum_drift(const std::vector<Vec3>& L) {
  if (L.empty() || L.front().norm() == 0.0) return 0.0;
  double worst = 0.0;
  for (const Vec3& l : L) worst = std::max(worst, (l - L.front()).norm());
  return worst / L.front().norm();
}

}  // namespace dropcheck
