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
  }
  return "?";
}

}  // namespace

std::string to_string(RotationLaw law) {
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
  }
  return s + (law.orientation == OrientationUpdate::first_order ? "; q = normalize(q + h/2*(0,w)*q)"
                                                                : "; q = exp(h/2*(0,w))*q");
}

std::string rotation_law_key(RotationLaw law) {
  return std::string(gyroscopic_key(law.gyroscopic)) +
         (law.orientation == OrientationUpdate::first_order ? "/first-order" : "/exp-map");
}

std::optional<RotationLaw> parse_rotation_law_key(std::string_view key) {
  for (RotationLaw law : kRotationFamily)
    if (rotation_law_key(law) == key) return law;
  return std::nullopt;
}

}  // namespace dropcheck
