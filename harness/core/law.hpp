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
// the damped velocity before the next step), so the family has five distinct members. Adding an
// engine or a scheme means naming its member here; every oracle then predicts it.
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
  SemiImplicit,  // x += h*v_{n+1}: every engine shipped with dropcheck
  Explicit,      // x += h*v_n: forward Euler
};

// One member of the family. Implicit from DampingOrder: a semi-implicit engine names only its
// order.
struct Law {
  DampingOrder damping = DampingOrder::AfterForces;
  PositionUpdate position = PositionUpdate::SemiImplicit;

  constexpr Law() = default;
  constexpr Law(DampingOrder d, PositionUpdate p = PositionUpdate::SemiImplicit)  // NOLINT
      : damping(d), position(p) {}
  friend constexpr bool operator==(const Law&, const Law&) = default;
};

// Every distinct member, in a fixed order (for identification and sweeps).
inline constexpr Law kLawFamily[] = {
    {DampingOrder::AfterForces, PositionUpdate::SemiImplicit},
    {DampingOrder::BeforeForces, PositionUpdate::SemiImplicit},
    {DampingOrder::AfterPosition, PositionUpdate::SemiImplicit},
    {DampingOrder::AfterForces, PositionUpdate::Explicit},
    {DampingOrder::BeforeForces, PositionUpdate::Explicit},
};

// One step of `law` on one coordinate or vector (Real: float, double, long double, or an Eigen
// vector of them). phi, h and a must already be in the arithmetic being modelled.
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

// "v = phi*(v + a*h); x += h*v" and so on: the member's update, as printed by `dropcheck engines`.
std::string to_string(Law law);
// A short stable key ("after-forces", "before-forces/explicit") for files and the command line.
std::string law_key(Law law);
std::optional<Law> parse_law_key(std::string_view key);

// What two members differ in, as a cause: "damping-order", "position-update", both joined by " + ",
// or "" for one member. With the explicit position update, AfterPosition and AfterForces are one
// member (see above); without damping (`damped` false: phi = 1) where it sits leaves no trace.
std::string law_difference(Law a, Law b, bool damped = true);

}  // namespace dropcheck
