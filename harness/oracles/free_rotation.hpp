// Oracle 1 for rotation: a torque-free rigid body's angular velocity in closed form.
//
// In the body's principal frame, with principal moments I1, I2, I3, Euler's equations without
// torque are
//   I1*w1' = (I2 - I3)*w2*w3,   I2*w2' = (I3 - I1)*w3*w1,   I3*w3' = (I1 - I2)*w1*w2,
// and they keep the kinetic energy E = (I1*w1^2 + I2*w2^2 + I3*w3^2)/2 and the magnitude of the
// angular momentum M^2 = I1^2*w1^2 + I2^2*w2^2 + I3^2*w3^2. With the axes ordered I1 < I2 < I3
// and M^2 > 2*E*I2 (the body turns about its axis of largest moment), the solution is (Landau and
// Lifshitz, Mechanics, section 37)
//   w1 = A1*cn(tau), w2 = A2*sn(tau), w3 = s*A3*dn(tau),   tau = s*lambda*t + tau0,
//   A1^2 = (2*E*I3 - M^2)/(I1*(I3 - I1)),   A2^2 = (2*E*I3 - M^2)/(I2*(I3 - I2)),
//   A3^2 = (M^2 - 2*E*I1)/(I3*(I3 - I1)),   lambda^2 = (I3 - I2)*(M^2 - 2*E*I1)/(I1*I2*I3),
//   modulus k^2 = (I2 - I1)*(2*E*I3 - M^2)/((I3 - I2)*(M^2 - 2*E*I1)),
// with s the sign of w3 (dn is never negative) and tau0 the phase of the initial state:
// cn(tau0) = w1(0)/A1, sn(tau0) = w2(0)/A2. For M^2 < 2*E*I2 (about the axis of least moment) the
// same holds with axes 1 and 3 swapped; a swap of two axes reverses the sign of Euler's equations,
// which the same swap applied to w = -w undoes (the equations are quadratic in w): the formula is
// applied to -w in any frame that is an odd permutation of the given axes, and tau runs backwards
// when axes 1 and 3 are swapped (free_rotation.cpp). Jacobi's
// functions and the elliptic integral of the first kind come from Boost.Math.
//
// w is periodic with period 4*K(k)/lambda. The component along the intermediate axis, w2, changes
// sign every 2*K(k)/lambda: for a body spun near that axis these are the flips of the Dzhanibekov
// effect. On the separatrix M^2 = 2*E*I2 (k = 1) the period is infinite: one flip at most.
#pragma once

#include <vector>

#include "harness/core/scene.hpp"

namespace dropcheck {

class FreeRotation {
 public:
  // `inertia`: the principal moments (kg m^2), in any order, each > 0, satisfying the triangle
  // inequality; `omega0`: the body-frame angular velocity at t = 0 (rad/s), along the same axes.
  // Throws std::invalid_argument for moments that break these conditions.
  FreeRotation(const Vec3& inertia, const Vec3& omega0);

  // The body-frame angular velocity at time t (rad/s), along the axes given to the constructor.
  Vec3 omega(double t) const;

  double energy() const { return energy_; }      // E = sum I_i w_i^2 / 2 (J)
  double momentum() const { return momentum_; }  // |M| = |I w| (kg m^2/s)
  // The period of w(t) (s); infinite for steady rotation (about a principal axis or of a sphere)
  // and on the separatrix.
  double period() const;
  // The times in [0, t_end] at which the component along the intermediate axis changes sign (the
  // flips of a body tumbling near it), in increasing order; none for steady or axisymmetric
  // rotation.
  std::vector<double> flips(double t_end) const;

 private:
  enum class Kind { steady, axisymmetric, elliptic };

  Kind kind_ = Kind::steady;
  Vec3 inertia_, omega0_;
  double energy_ = 0.0, momentum_ = 0.0;
  // elliptic: the frame the formula works in (ordered so that axis_[1] is the intermediate one),
  // the sign flip of that frame, the amplitudes, rate, modulus and phase.
  int axis_[3] = {0, 1, 2};
  double flip_ = 1.0;   // -1 when the formula's frame is an odd permutation (it runs on -w)
  double sign3_ = 1.0;  // the sign of w3 in the formula's frame
  double a1_ = 0.0, a2_ = 0.0, a3_ = 0.0, lambda_ = 0.0, k_ = 0.0, tau0_ = 0.0;
  double s_ = 1.0;  // the sign of tau's rate: sign3_, reversed when axes 1 and 3 were swapped
  // axisymmetric: the symmetry axis, the rate of the perpendicular components' rotation.
  int sym_ = 0;
  double precession_ = 0.0;
};

}  // namespace dropcheck
