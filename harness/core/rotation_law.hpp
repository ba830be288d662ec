// The rotational members of the discrete-law family: how a fixed-step engine turns a free body in
// one step of h. Rotation is more state beside the linear law (law.hpp), not a second family: the
// angular damping factor phi_a = exp(-k_a*h) sits where the engine's linear damping sits
// (DampingOrder), and the gyroscopic term is a force like any other, taken from the angular
// velocity the forces see.
//
// With R the rotation of q at the step start, I the principal moments (body frame), the world
// inertia I_w = R*diag(I)*R^T, L = I_w*w and tau the external torque (world frame), one step is:
//   BeforeForces:   w = phi_a*w;  w = G(w) + h*I_w^-1*tau;  q = Q(q, w)
//   AfterForces:    w = G(w) + h*I_w^-1*tau;  w = phi_a*w;  q = Q(q, w)
//   AfterPosition:  w = G(w) + h*I_w^-1*tau;  q = Q(q, w);  w = phi_a*w
// and with the explicit position update (law.hpp: Chipmunk) q = Q(q, w) comes first, with the
// step-start w.
// where the gyroscopic update G (Euler's equations' w x (I_w*w) term) is one of
//   none               G(w) = w                                       (the term left out)
//   explicit           G(w) = w - h*I_w^-1*(w x I_w*w)                 (at the step start)
//   implicit body      in body coordinates w_b = R^T*w, one Newton step on
//                      f(w') = I*(w' - w_b) + h*w' x (I*w') = 0 from w' = w_b:
//                      w'_b = w_b - J^-1*(h*w_b x I*w_b), J = I + h*(S(w_b)*I - S(I*w_b));
//                      G(w) = R*w'_b                                   (Bullet's default)
//   linearly implicit  G(w) = (I_w - h*S(L))^-1*L                      (Lacoursiere; ODE >= 0.13)
// (S(a) is the cross-product matrix, S(a)*b = a x b), and the orientation update Q is one of
//   first order        q = normalize(q + (h/2)*(0, w)*q)
//   exponential map    q = normalize((cos(|w|h/2), sin(|w|h/2)*w/|w|)*q)   (exact for constant w)
// A torque-free body keeps |L| under the implicit members only to first order; the explicit one
// gains energy, none precesses wrongly: the members differ at order h, which is what lets
// `identify` tell them apart from a trajectory.
//
// The RK4 member (linear law kRungeKutta4, Wild Magic) is no G and Q pair: its state is (q, L) with
// L the world angular momentum, and one step is the four classical stages of
//   q' = (1/2)*(0, w)*q,  L' = tau - k_a*L,  w = R(q)*diag(I)^-1*R(q)^T*L
// (advance_rotation_rk4 below), with R(q) the rotation matrix formula applied to q as it is: q is
// never renormalised. Without torque L stays exactly constant (conserved by construction), and the
// gyroscopic motion comes from w = I_w^-1*L at each stage, not from a term to approximate.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "harness/core/law.hpp"

namespace dropcheck {

enum class Gyroscopic {
  none,               // the w x (I_w*w) term is left out
  explicit_term,      // evaluated at the step start (ours, MuJoCo)
  implicit_body,      // one Newton step in body coordinates (Bullet's default flag)
  linearly_implicit,  // (I_w - h*S(L))^-1*L (ODE since 0.13, on by default)
  momentum,           // L is the state, w = I_w^-1*L at each RK4 stage (Wild Magic)
};

enum class OrientationUpdate {
  first_order,      // normalize(q + (h/2)*(0, w)*q) (ours, ODE)
  exponential_map,  // the exact rotation by w*h (Bullet, MuJoCo, Box2D's angle += h*w)
  rk4,              // the RK4 stages of q' = (1/2)*(0, w)*q, never renormalised (Wild Magic)
};

struct RotationLaw {
  Gyroscopic gyroscopic = Gyroscopic::explicit_term;
  OrientationUpdate orientation = OrientationUpdate::first_order;
  // The engine keeps the orientation as a rotation vector (angle times axis, at most pi) and
  // rebuilds the rotation from it at every step (DART's FreeJoint). In exact arithmetic this is the
  // same member; it changes only the rounding, which the own-law prediction repeats
  // (harness/oracles/own_arithmetic.hpp). Members compare equal whatever they store.
  bool rotation_vector = false;
  // Its gyroscopic force is the bias of the body's 6-D velocity (w, v) in body coordinates (DART's
  // spatial algebra): the torque w x I*w + v x m*v, whose second term is zero in exact arithmetic
  // but rounds to up to 2*eps*m*|v|^2 at every step, a rounding the own-law tolerance takes in.
  bool spatial_bias = false;
  friend constexpr bool operator==(const RotationLaw& a, const RotationLaw& b) {
    return a.gyroscopic == b.gyroscopic && a.orientation == b.orientation;
  }
};

// Every member, in a fixed order (for identification).
inline constexpr RotationLaw kRotationFamily[] = {
    {Gyroscopic::none, OrientationUpdate::first_order},
    {Gyroscopic::none, OrientationUpdate::exponential_map},
    {Gyroscopic::explicit_term, OrientationUpdate::first_order},
    {Gyroscopic::explicit_term, OrientationUpdate::exponential_map},
    {Gyroscopic::implicit_body, OrientationUpdate::first_order},
    {Gyroscopic::implicit_body, OrientationUpdate::exponential_map},
    {Gyroscopic::linearly_implicit, OrientationUpdate::first_order},
    {Gyroscopic::linearly_implicit, OrientationUpdate::exponential_map},
    {Gyroscopic::momentum, OrientationUpdate::rk4},  // with the linear law kRungeKutta4 only
};

inline constexpr RotationLaw kRotationRk4{Gyroscopic::momentum, OrientationUpdate::rk4};

// "explicit + first order" and the like, as printed by `dropcheck engines`.
std::string to_string(RotationLaw law);
// A short stable key ("explicit/first-order", "implicit-body/exp-map") for files and the command
// line.
std::string rotation_law_key(RotationLaw law);
std::optional<RotationLaw> parse_rotation_law_key(std::string_view key);

// One body's rotational state and constants in the arithmetic Real (double or long double).
template <class Real>
struct Spin {
  using V = Eigen::Matrix<Real, 3, 1>;
  using M = Eigen::Matrix<Real, 3, 3>;
  Eigen::Quaternion<Real> q = Eigen::Quaternion<Real>::Identity();
  V w = V::Zero();  // world frame
  V L = V::Zero();  // world angular momentum: the state of the RK4 member (unused by the others)
};

namespace rotation_detail {

template <class Real>
Eigen::Matrix<Real, 3, 3> cross_matrix(const Eigen::Matrix<Real, 3, 1>& a) {
  Eigen::Matrix<Real, 3, 3> s;
  s << Real(0), -a.z(), a.y(), a.z(), Real(0), -a.x(), -a.y(), a.x(), Real(0);
  return s;
}

// G(w) of the member (the comment at the top), R the rotation at the step start.
template <class Real>
Eigen::Matrix<Real, 3, 1> gyroscopic_update(Gyroscopic g, const Eigen::Matrix<Real, 3, 3>& R,
                                            const Eigen::Matrix<Real, 3, 1>& inertia, Real h,
                                            const Eigen::Matrix<Real, 3, 1>& w) {
  using V = Eigen::Matrix<Real, 3, 1>;
  const V wb = R.transpose() * w;
  const V Lb = inertia.cwiseProduct(wb);
  switch (g) {
    case Gyroscopic::none:
    case Gyroscopic::momentum:  // the RK4 member steps in advance_rotation_rk4, never here
      return w;
    case Gyroscopic::explicit_term:
      return w - R * (h * wb.cross(Lb)).cwiseQuotient(inertia);
    case Gyroscopic::implicit_body: {
      const Eigen::Matrix<Real, 3, 3> J =
          Eigen::Matrix<Real, 3, 3>(inertia.asDiagonal()) +
          h * (cross_matrix(wb) * inertia.asDiagonal() - cross_matrix(Lb));
      return R * (wb - J.lu().solve(h * wb.cross(Lb)));
    }
    case Gyroscopic::linearly_implicit: {
      const Eigen::Matrix<Real, 3, 3> Iw = R * inertia.asDiagonal() * R.transpose();
      const V L = Iw * w;
      return (Iw - h * cross_matrix(L)).lu().solve(L);
    }
  }
  return w;
}

// Q(q, w): the orientation after one step of h at the world angular velocity w.
template <class Real>
Eigen::Quaternion<Real> orientation_update(OrientationUpdate u, const Eigen::Quaternion<Real>& q,
                                           const Eigen::Matrix<Real, 3, 1>& w, Real h) {
  using Q = Eigen::Quaternion<Real>;
  Q out;
  if (u == OrientationUpdate::first_order) {
    out.coeffs() = q.coeffs() + (Q(Real(0), w.x(), w.y(), w.z()) * q).coeffs() * (h / Real(2));
  } else {
    const Real angle = w.norm() * h;  // sin(angle/2)/|w| -> h/2 as |w| -> 0
    const Real s = angle > Real(0) ? std::sin(angle / Real(2)) / w.norm() : h / Real(2);
    const Q turn(std::cos(angle / Real(2)), s * w.x(), s * w.y(), s * w.z());
    out = turn * q;
  }
  out.normalize();
  return out;
}

}  // namespace rotation_detail

// One step of member `law` with the angular damping factor phi_a placed as the engine's linear
// member `linear` places the linear one, on a body of principal moments `inertia` under world
// torque `torque`. With the explicit position update (law.hpp) the orientation turns with the
// step-start w, before w changes, as the position moves with the step-start v.
template <class Real>
void advance_rotation(RotationLaw law, Law linear, Real phi_a, Real h,
                      const Eigen::Matrix<Real, 3, 1>& inertia,
                      const Eigen::Matrix<Real, 3, 1>& torque, Spin<Real>& s) {
  const Eigen::Matrix<Real, 3, 3> R = s.q.toRotationMatrix();
  const DampingOrder damping = linear.damping;
  if (linear.position == PositionUpdate::Explicit)
    s.q = rotation_detail::orientation_update(law.orientation, s.q, s.w, h);
  if (damping == DampingOrder::BeforeForces) s.w *= phi_a;
  s.w = rotation_detail::gyroscopic_update(law.gyroscopic, R, inertia, h, s.w) +
        R * (h * (R.transpose() * torque)).cwiseQuotient(inertia);
  if (damping == DampingOrder::AfterForces) s.w *= phi_a;
  if (linear.position == PositionUpdate::SemiImplicit)
    s.q = rotation_detail::orientation_update(law.orientation, s.q, s.w, h);
  if (damping == DampingOrder::AfterPosition) s.w *= phi_a;
}

// One step of the RK4 member (the comment at the top) with angular damping rate k_a, on a body of
// principal moments `inertia` under the world torque `torque`, in the order of Wild Magic's
// RigidBody::Update. s.L must hold the body's angular momentum; s.w is derived from it.
template <class Real>
void advance_rotation_rk4(Real k_a, Real h, const Eigen::Matrix<Real, 3, 1>& inertia,
                          const Eigen::Matrix<Real, 3, 1>& torque, Spin<Real>& s) {
  using V = Eigen::Matrix<Real, 3, 1>;
  using Q = Eigen::Quaternion<Real>;
  const auto spin_of = [&](const Q& q, const V& L) -> V {
    const Eigen::Matrix<Real, 3, 3> R = q.toRotationMatrix();  // q as it is, like Wild Magic
    return R * (R.transpose() * L).cwiseQuotient(inertia);
  };
  const auto dq = [](const Q& q, const V& w) -> Eigen::Matrix<Real, 4, 1> {
    return (Q(Real(0), w.x(), w.y(), w.z()) * q).coeffs() / Real(2);
  };
  const auto shifted = [](const Q& q, Real t, const Eigen::Matrix<Real, 4, 1>& d) {
    Q out;
    out.coeffs() = q.coeffs() + t * d;
    return out;
  };
  const Real half = h / Real(2);
  const Q q0 = s.q;
  const V L0 = s.L;
  const Eigen::Matrix<Real, 4, 1> a1 = dq(q0, s.w);
  const V b1 = torque - k_a * L0;
  const Q q2 = shifted(q0, half, a1);
  const V L2 = L0 + half * b1;
  const Eigen::Matrix<Real, 4, 1> a2 = dq(q2, spin_of(q2, L2));
  const V b2 = torque - k_a * L2;
  const Q q3 = shifted(q0, half, a2);
  const V L3 = L0 + half * b2;
  const Eigen::Matrix<Real, 4, 1> a3 = dq(q3, spin_of(q3, L3));
  const V b3 = torque - k_a * L3;
  const Q q4 = shifted(q0, h, a3);
  const V L4 = L0 + h * b3;
  const Eigen::Matrix<Real, 4, 1> a4 = dq(q4, spin_of(q4, L4));
  const V b4 = torque - k_a * L4;
  const Real sixth = h / Real(6);
  s.q = shifted(q0, sixth, a1 + Real(2) * (a2 + a3) + a4);
  s.L = L0 + sixth * (b1 + Real(2) * (b2 + b3) + b4);
  s.w = spin_of(s.q, s.L);
}

}  // namespace dropcheck
