#include "harness/core/bounce_law.hpp"

#include <cmath>

#include "harness/core/number_format.hpp"

namespace dropcheck {

std::string describe(const BounceLaw& law) {
  std::string text = "restitution of the step-start approach speed";
  if (law.threshold > 0.0) text += printf_string(" above %.6g m/s", law.threshold);
  if (law.erp > 0.0) {
    text += printf_string(", push-out %.6g*depth/h", law.erp);
    if (std::isfinite(law.max_push)) text += printf_string(" capped at %.6g m/s", law.max_push);
  }
  return text;
}

}  // namespace dropcheck
