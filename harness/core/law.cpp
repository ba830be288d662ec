#include "harness/core/law.hpp"

namespace dropcheck {

std::string to_string(Law law) {
  if (law.scheme == Scheme::RK4) return "RK4: x' = v, v' = a - k*v, 4 stages";
  if (law.scheme == Scheme::ErrorControlled) return "x' = v, v' = a - k*v, error-controlled";
  const bool explicit_x = law.position == PositionUpdate::Explicit;
  switch (law.damping) {
    case DampingOrder::AfterForces:
      return explicit_x ? "x += h*v; v = phi*(v + a*h)" : "v = phi*(v + a*h); x += h*v";
    case DampingOrder::BeforeForces:
      return explicit_x ? "x += h*v; v = phi*v + a*h" : "v = phi*v + a*h; x += h*v";
    case DampingOrder::AfterPosition:
      return explicit_x ? "x += h*v; v = phi*(v + a*h)" : "v' = v + a*h; x += h*v'; v = phi*v'";
  }
  return "?";
}

std::string law_difference(Law a, Law b, bool damped) {
  auto order = [](Law l) {
    return l.position == PositionUpdate::Explicit && l.damping == DampingOrder::AfterPosition
               ? DampingOrder::AfterForces
               : l.damping;
  };
  if (a.scheme != b.scheme) return "scheme";
  if (a.scheme != Scheme::Euler) return "";
  std::string out;
  if (damped && order(a) != order(b)) out = "damping-order";
  if (a.position != b.position) out += (out.empty() ? "" : " + ") + std::string("position-update");
  return out;
}

std::string law_key(Law law) {
  if (law.scheme == Scheme::RK4) return "rk4";
  if (law.scheme == Scheme::ErrorControlled) return "error-controlled";
  std::string key = law.damping == DampingOrder::AfterForces    ? "after-forces"
                    : law.damping == DampingOrder::BeforeForces ? "before-forces"
                                                                : "after-position";
  if (law.position == PositionUpdate::Explicit) key += "/explicit";
  return key;
}

std::optional<Law> parse_law_key(std::string_view key) {
  if (key == law_key(kRungeKutta4)) return kRungeKutta4;
  if (key == law_key(kErrorControlled)) return kErrorControlled;
  for (DampingOrder d :
       {DampingOrder::AfterForces, DampingOrder::BeforeForces, DampingOrder::AfterPosition})
    for (PositionUpdate p : {PositionUpdate::SemiImplicit, PositionUpdate::Explicit})
      if (law_key({d, p}) == key) return Law{d, p};
  return std::nullopt;
}

}  // namespace dropcheck
