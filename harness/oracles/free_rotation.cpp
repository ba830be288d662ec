#include "harness/oracles/free_rotation.hpp"

#include <algorithm>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace dropcheck {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

void check_moments(const Vec3& I) {
  for (int i = 0; i < 3; ++i)
    if (!(std::isfinite(I[i]) && I[i] > 0.0))
      throw std::invalid_argument("principal moments must be finite and > 0");
  for (int i = 0; i < 3; ++i)
    if (I[i] > I[(i + 1) % 3] + I[(i + 2) % 3])
      throw std::invalid_argument("principal moments break the triangle inequality");
}

// True when w lies along one principal axis (or is zero): then it never changes.
bool along_one_axis(const Vec3& w) {
  int nonzero = 0;
  for (int i = 0; i < 3; ++i) nonzero += w[i] != 0.0;
  return nonzero <= 1;
}

}  // namespace

FreeRotation::FreeRotation(const Vec3& inertia, const Vec3& omega0)
    : inertia_(inertia), omega0_(omega0) {
  check_moments(inertia);
  const Vec3 L = inertia.cwiseProduct(omega0);
  energy_ = 0.5 * omega0.dot(L);
  momentum_ = L.norm();
  const double& Ia = inertia[0];
  const double& Ib = inertia[1];
  const double& Ic = inertia[2];
  if ((Ia == Ib && Ib == Ic) || along_one_axis(omega0)) {
    kind_ = Kind::steady;
    return;
  }
  if (Ia == Ib || Ib == Ic || Ia == Ic) {
    // Axisymmetric: for the symmetry axis s and the others p, q in cyclic order (s, p, q), Euler's
    // equations give w_s' = 0, w_p' = -W*w_q, w_q' = W*w_p with W = (I_s - I_perp)/I_perp * w_s:
    // (w_p, w_q) turns at the constant rate W.
    kind_ = Kind::axisymmetric;
    sym_ = Ib == Ic ? 0 : (Ia == Ic ? 1 : 2);
    const double perp = inertia[(sym_ + 1) % 3];
    precession_ = (inertia[sym_] - perp) / perp * omega0[sym_];
    return;
  }
  kind_ = Kind::elliptic;
  std::iota(axis_, axis_ + 3, 0);
  std::sort(axis_, axis_ + 3, [&](int a, int b) { return inertia[a] < inertia[b]; });
  const double two_e = 2.0 * energy_, m2 = momentum_ * momentum_;
  double order = 1.0;                    // -1: the formula's axes 1 and 3 swapped
  if (m2 < two_e * inertia[axis_[1]]) {  // about the axis of least moment: swap axes 1 and 3
    std::swap(axis_[0], axis_[2]);
    order = -1.0;
  }
  // An odd permutation of the given axes reverses the sign of Euler's equations: the formula then
  // runs on -w (the equations are quadratic in w).
  const bool odd = (axis_[0] > axis_[1]) + (axis_[0] > axis_[2]) + (axis_[1] > axis_[2]) == 1 ||
                   (axis_[0] > axis_[1]) + (axis_[0] > axis_[2]) + (axis_[1] > axis_[2]) == 3;
  flip_ = odd ? -1.0 : 1.0;
  const double I1 = inertia[axis_[0]], I2 = inertia[axis_[1]], I3 = inertia[axis_[2]];
  const double x = flip_ * omega0[axis_[0]], y = flip_ * omega0[axis_[1]],
               z = flip_ * omega0[axis_[2]];
  // In the swapped frame each factor below changes sign in pairs, so every ratio stays >= 0; a
  // rounding below 0 next to a principal axis is clamped.
  const double top = std::max(0.0, (two_e * I3 - m2) / (I3 - I1));
  const double bottom = std::max(0.0, (m2 - two_e * I1) / (I3 - I1));
  a1_ = std::sqrt(top / I1);
  a2_ = std::sqrt(top * (I3 - I1) / (I2 * (I3 - I2)));
  a3_ = std::sqrt(bottom / I3);
  lambda_ = std::sqrt((I3 - I2) * (I3 - I1) * bottom / (I1 * I2 * I3));
  const double k2 = (I2 - I1) * top / ((I3 - I2) * bottom);
  k_ = std::sqrt(std::clamp(k2, 0.0, 1.0));
  // s: dn is never negative, so the sign of w3 is carried apart. With axes 1 and 3 swapped the
  // factors (I3 - I1), (I3 - I2) and (I2 - I1) of the identities that make the formula solve
  // Euler's equations (A2*lambda = (I3 - I1)/I2*A1*A3 and its two cyclic siblings) are all
  // negative, so tau runs backwards there.
  sign3_ = z < 0.0 ? -1.0 : 1.0;
  s_ = sign3_ * order;
  // The phase: cn(tau0) = x/A1, sn(tau0) = y/A2, so that the amplitude am(tau0) = atan2(y/A2,
  // x/A1) and tau0 = F(am(tau0) | k).
  tau0_ = boost::math::ellint_1(k_, std::atan2(y / a2_, x / a1_));
}

Vec3 FreeRotation::omega(double t) const {
  switch (kind_) {
    case Kind::steady:
      return omega0_;
    case Kind::axisymmetric: {
      const int p = (sym_ + 1) % 3, q = (sym_ + 2) % 3;
      const double c = std::cos(precession_ * t), s = std::sin(precession_ * t);
      Vec3 w = omega0_;
      w[p] = omega0_[p] * c - omega0_[q] * s;
      w[q] = omega0_[p] * s + omega0_[q] * c;
      return w;
    }
    case Kind::elliptic:
      break;
  }
  double cn = 0.0, dn = 0.0;
  const double sn = boost::math::jacobi_elliptic(k_, s_ * lambda_ * t + tau0_, &cn, &dn);
  Vec3 w;
  w[axis_[0]] = flip_ * a1_ * cn;
  w[axis_[1]] = flip_ * a2_ * sn;
  w[axis_[2]] = flip_ * sign3_ * a3_ * dn;
  return w;
}

double FreeRotation::period() const {
  switch (kind_) {
    case Kind::steady:
      return kInfinity;
    case Kind::axisymmetric:
      return precession_ == 0.0 ? kInfinity : 2.0 * M_PI / std::abs(precession_);
    case Kind::elliptic:
      break;
  }
  return k_ >= 1.0 ? kInfinity : 4.0 * boost::math::ellint_1(k_) / lambda_;
}

std::vector<double> FreeRotation::flips(double t_end) const {
  std::vector<double> out;
  if (kind_ != Kind::elliptic || k_ >= 1.0 || !(t_end > 0.0)) return out;
  // w2 = A2*sn(tau) is zero at tau = 2*n*K; tau runs from tau0 to tau0 + s*lambda*t_end.
  const double two_k = 2.0 * boost::math::ellint_1(k_);
  const double tau_end = tau0_ + s_ * lambda_ * t_end;
  const double lo = std::min(tau0_, tau_end), hi = std::max(tau0_, tau_end);
  for (double n = std::ceil(lo / two_k); n * two_k <= hi; n += 1.0) {
    const double t = (n * two_k - tau0_) / (s_ * lambda_);
    if (t > 0.0 && t <= t_end) out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace dropcheck
