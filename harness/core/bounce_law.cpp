#include "harness/core/bounce_law.hpp"

#include <cmath>

#include "harness/core/number_format.hpp"

namespace dropcheck {

std::string push_text(const BounceLaw& law) {
  std::string text = printf_string("push-out %.6g*depth/h", law.erp);
  if (std::isfinite(law.max_push)) text += printf_string(" capped at %.6g m/s", law.max_push);
  return text + (law.push_in_position ? " in position (split impulse)" : "");
}

std::string contact_distance_text(const BounceLaw& law) {
  std::string text = "speculative contact within ";
  if (law.contact_distance > 0.0) text += printf_string("%.6g m", law.contact_distance);
  if (law.contact_distance > 0.0 && law.contact_distance_per_size > 0.0) text += " + ";
  if (law.contact_distance_per_size > 0.0)
    text += printf_string("%.6g x the bounding half diagonal", law.contact_distance_per_size);
  return text;
}

std::string describe(const BounceLaw& law) {
  std::string text = "restitution of the step-start approach speed";
  if (law.threshold > 0.0) text += printf_string(" above %.6g m/s", law.threshold);
  if (law.erp > 0.0) text += ", " + push_text(law);
  if (law.contact_distance > 0.0 || law.contact_distance_per_size > 0.0)
    text += ", " + contact_distance_text(law);
  if (law.touching) text += ", a touch (gap 0) is a contact";
  return text;
}

}  // namespace dropcheck
