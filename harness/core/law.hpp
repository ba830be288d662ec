// The discrete-law family: how a fixed-step Euler engine advances a free body in one step of h.
//
// A free body with acceleration a = g + F/m (F evaluated by the harness at the start of the step)
// and per-step velocity decay phi = exp(-k*h) is advanced by every engine dropcheck knows as one
// member of a 3 x 2 family:
//   where the damping sits (DampingOrder)       x   which velocity moves the position
//   BeforeForces:  v = phi*v + a*h                   SemiImplicit: x += h*v_new  (symplectic Euler)
//   AfterForces:   v = phi*(v + a*h)                 Explicit:     x += h*v_old  (forward Euler)
//   AfterPosition: v' = v + a*h; ...; v = phi*v'
// With Explicit, AfterPosition and AfterForces give the same trajectory (the position never sees
// the damped velocity before the next step), so the family has five distinct Euler members.
//
// A sixth member is not Euler at all: the classical fourth-order Runge-Kutta scheme (Scheme::RK4,
// Wild Magic's RigidBody::Update), which evaluates the forces at four stages of the step and damps
// through the force -k*v rather than a per-step factor (advance_rk4 below). A seventh has no
// fixed step: an error-controlled integrator (Scheme::ErrorControlled, Simbody's
// Runge-Kutta-Merson) picks its own steps to hold an estimate of each step's error under a
// requested accuracy, so its law is the continuous model itself, met within that accuracy rather
// than to rounding (harness/judge/own_law.cpp says how far). Adding an engine or a scheme means
// naming its member here; every oracle then predicts it.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace dropcheck {

// Where an engine applies the per-step damping factor phi relative to the velocity and position
// updates of a free body.
enum class DampingOrder {
  AfterForces,    // ours, Box2D, MuJoCo:  v = phi*(v + a*h)
  BeforeForces,   // Bullet:               v = phi*v + a*h
  AfterPosition,  // ODE:                  v' = v + a*h;  x += h*v';  v = phi*v'
};

// Which velocity the position update uses.
enum class PositionUpdate {
  SemiImplicit,  // x += h*v_{n+1}: every engine shipped with dropcheck but Chipmunk
  Explicit,      // x += h*v_n: forward Euler (Chipmunk)
};

// How many times a step evaluates the forces.
enum class Scheme {
  Euler,            // once, at the step start: the five members above (every engine but Wild Magic)
  RK4,              // four stages, classical Runge-Kutta; damping is the force -m*k*v (Wild Magic)
  ErrorControlled,  // variable steps under a requested accuracy; damping is the force -m*k*v
};

// One member of the family. Implicit from DampingOrder: a semi-implicit engine names only its
// order. An RK4 member leaves damping and position at their defaults (they mean nothing to it).
struct Law {
  DampingOrder damping = DampingOrder::AfterForces;
  PositionUpdate position = PositionUpdate::SemiImplicit;
  Scheme scheme = Scheme::Euler;

  constexpr Law() = default;
  constexpr Law(DampingOrder d, PositionUpdate p = PositionUpdate::SemiImplicit)  // NOLINT
      : damping(d), position(p) {}
  constexpr explicit Law(Scheme s) : scheme(s) {}
  friend constexpr bool operator==(const Law&, const Law&) = default;
};

inline constexpr Law kRungeKutta4{Scheme::RK4};
inline constexpr Law kErrorControlled{Scheme::ErrorControlled};

// Every distinct fixed-step member, in a fixed order (for identification and sweeps). The
// error-controlled member is not among them: no trajectory at one accuracy tells it apart from the
// continuous model, so it is declared, never fitted.
inline constexpr Law kLawFamily[] = {
    {DampingOrder::AfterForces, PositionUpdate::SemiImplicit},
    {DampingOrder::BeforeForces, PositionUpdate::SemiImplicit},
    {DampingOrder::AfterPosition, PositionUpdate::SemiImplicit},
    {DampingOrder::AfterForces, PositionUpdate::Explicit},
    {DampingOrder::BeforeForces, PositionUpdate::Explicit},
    kRungeKutta4,
};

// The order of convergence of a member: its global error shrinks as h^order (1 for every Euler
// member, 4 for RK4; 0 for the error-controlled member, whose error follows its accuracy, not h).
constexpr int order_of(Law law) {
  switch (law.scheme) {
    case Scheme::Euler:
      return 1;
    case Scheme::RK4:
      return 4;
    case Scheme::ErrorControlled:
      return 0;
  }
  return 1;
}

// One step of an Euler member (law.scheme == Scheme::Euler) on one coordinate or vector (Real:
// float, double, long double, or an Eigen vector of them). phi, h and a must already be in the
// arithmetic being modelled.
template <class Vec, class Real>
constexpr void advance(Law law, Real phi, Real h, const Vec& a, Vec& x, Vec& v) {
  if (law.position == PositionUpdate::Explicit) {
    x += h * v;
    switch (law.damping) {
      case DampingOrder::BeforeForces:
        v = phi * v + a * h;
        return;
      case DampingOrder::AfterForces:
      case DampingOrder::AfterPosition:
        v = phi * (v + a * h);
        return;
    }
    return;
  }
  switch (law.damping) {
    case DampingOrder::AfterForces:
      v = phi * (v + a * h);
      x += h * v;
      return;
    case DampingOrder::BeforeForces:
      v = phi * v + a * h;
      x += h * v;
      return;
    case DampingOrder::AfterPosition:
      v += a * h;
      x += h * v;
      v *= phi;
      return;
  }
}

// One step of the RK4 member: x' = v, v' = accel(x, v) - k*v with the four classical stages
//   s1 = (v, f(x, v)),  s2 = f at (x, v) + h/2*s1,  s3 = f at (x, v) + h/2*s2,  s4 = f at + h*s3
//   (x, v) += h/6*(s1 + 2*s2 + 2*s3 + s4)
// in the order Wild Magic's RigidBody::Update takes them (on momentum; the same up to rounding).
// `accel(x, v)` is the acceleration without the damping (gravity and forces at that stage's
// state). For a constant accel = a the velocity step is, with u = k*h,
//   v' = R*v + h*T*a,  R = 1 - u + u^2/2 - u^3/6 + u^4/24 (exp(-u) to O(u^5): the per-step decay),
//   T = 1 - u/2 + u^2/6 - u^3/24 (so that R = 1 - u*T);
// |R| <= 1 needs u <= 2.785: RK4 damps only up to that step, where every Euler member's phi =
// exp(-u) damps at any step. Without damping it is exact for a constant a (x is quadratic in t).
template <class Vec, class Real, class Accel>
constexpr void advance_rk4(Real k, Real h, const Accel& accel, Vec& x, Vec& v) {
  const Real half = h / Real(2);
  auto f = [&](const Vec& xs, const Vec& vs) -> Vec { return accel(xs, vs) - k * vs; };
  const Vec v1 = v, a1 = f(x, v);
  const Vec x2 = x + half * v1, v2 = v + half * a1, a2 = f(x2, v2);
  const Vec x3 = x + half * v2, v3 = v + half * a2, a3 = f(x3, v3);
  const Vec x4 = x + h * v3, v4 = v + h * a3, a4 = f(x4, v4);
  const Real sixth = h / Real(6);
  x = x + sixth * (v1 + Real(2) * (v2 + v3) + v4);
  v = v + sixth * (a1 + Real(2) * (a2 + a3) + a4);
}

// R(u) above: the factor an RK4 step keeps of a velocity damped at rate k, u = k*h (u >= 0), and
// T(u) with R = 1 - u*T (the share of h*a a constant acceleration adds).
template <class Real>
constexpr Real rk4_gain(Real u) {
  return Real(1) - u / Real(2) + u * u / Real(6) - u * u * u / Real(24);
}
template <class Real>
constexpr Real rk4_decay(Real u) {
  return Real(1) - u * rk4_gain(u);
}

// "v = phi*(v + a*h); x += h*v" and so on: the member's update, as printed by `dropcheck engines`.
std::string to_string(Law law);
// A short stable key ("after-forces", "before-forces/explicit") for files and the command line.
std::string law_key(Law law);
std::optional<Law> parse_law_key(std::string_view key);

// What two members differ in, as a cause: "damping-order", "position-update", both joined by " + ",
// "scheme" (RK4 against an Euler member: everything differs, the order first), or "" for one
// member. With the explicit position update, AfterPosition and AfterForces are one
// member (see above); without damping (`damped` false: phi = 1) where it sits leaves no trace.
std::string law_difference(Law a, Law b, bool damped = true);

}  // namespace dropcheck
