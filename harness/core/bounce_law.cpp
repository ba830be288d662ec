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

std::string restitution_text(const BounceLaw& law) {
  std::string text = law.free_approach
                         ? "restitution of the approach speed after the step's gravity"
                         : "restitution of the step-start approach speed";
  if (law.threshold > 0.0)
    text += printf_string(
        law.threshold_on_rebound ? ", when the rebound exceeds %.6g m/s" : " above %.6g m/s",
        law.threshold);
  if (std::isfinite(law.max_rebound))
    text += printf_string(", capped at %.6g m/s", law.max_rebound);
  return text;
}

std::string cfm_text(const BounceLaw& law) {
  return printf_string("constraint force mixing %.6g of the row's diagonal entry", law.cfm);
}

std::string describe(const BounceLaw& law) {
  std::string text = restitution_text(law);
  if (law.erp > 0.0) text += ", " + push_text(law);
  if (law.contact_distance > 0.0 || law.contact_distance_per_size > 0.0)
    text += ", " + contact_distance_text(law);
  if (law.touching) text += ", a touch (gap 0) is a contact";
  if (law.cfm > 0.0) text += ", " + cfm_text(law);
  if (law.resolved_after_position) text += ", the contact resolved after the position update";
  return text;
}

}  // namespace dropcheck
