#include "harness/core/rotation_law.hpp"

namespace dropcheck {
namespace {

const char* gyroscopic_key(Gyroscopic g) {
  switch (g) {
    case Gyroscopic::none:
      return "no-gyro";
    case Gyroscopic::explicit_term:
      return "explicit";
    case Gyroscopic::implicit_body:
      return "implicit-body";
    case Gyroscopic::linearly_implicit:
      return "linearly-implicit";
    case Gyroscopic::momentum:
      return "momentum";
  }
  return "?";
}

const char* orientation_key(OrientationUpdate u) {
  switch (u) {
    case OrientationUpdate::first_order:
      return "/first-order";
    case OrientationUpdate::exponential_map:
      return "/exp-map";
    case OrientationUpdate::rk4:
      return "/rk4";
  }
  return "/?";
}

}  // namespace

std::string to_string(RotationLaw law) {
  if (law == kRotationRk4) return "RK4 on (q, L): q' = (0,w)*q/2, L' = tau - k_a*L, w = I_w^-1*L";
  std::string s;
  switch (law.gyroscopic) {
    case Gyroscopic::none:
      s = "no gyroscopic term";
      break;
    case Gyroscopic::explicit_term:
      s = "w -= h*I_w^-1*(w x I_w*w)";
      break;
    case Gyroscopic::implicit_body:
      s = "implicit body-frame gyro (one Newton step)";
      break;
    case Gyroscopic::linearly_implicit:
      s = "w = (I_w - h*S(L))^-1*L";
      break;
    case Gyroscopic::momentum:
      s = "w = I_w^-1*L";
      break;
  }
  switch (law.orientation) {
    case OrientationUpdate::first_order:
      s += "; q = normalize(q + h/2*(0,w)*q)";
      break;
    case OrientationUpdate::exponential_map:
      s += "; q = exp(h/2*(0,w))*q";
      break;
    case OrientationUpdate::rk4:
      s += "; q by RK4 stages";
      break;
  }
  return law.rotation_vector ? s + ", kept as a rotation vector" : s;
}

std::string rotation_law_key(RotationLaw law) {
  return std::string(gyroscopic_key(law.gyroscopic)) + orientation_key(law.orientation);
}

std::optional<RotationLaw> parse_rotation_law_key(std::string_view key) {
  for (RotationLaw law : kRotationFamily)
    if (rotation_law_key(law) == key) return law;
  return std::nullopt;
}

}  // namespace dropcheck
