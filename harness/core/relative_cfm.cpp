#include "harness/core/relative_cfm.hpp"

#include <algorithm>
#include <cmath>

#include "harness/core/number_format.hpp"

namespace dropcheck {

double contact_step(const RelativeCfm& law, double v_free, double h, NormalState& s) {
  if (law.cfm == 0.0) {  // rigid: the contact cancels the approach, nothing sinks
    s.v = 0.0;
    return -v_free;
  }
  const double push = std::min(law.erp * s.d / h, law.max_push);
  // The LCP's normal impulse is never negative: the contact only pushes (v_n' >= v_free).
  s.v = std::max(v_free, (law.cfm * v_free + push) / (1.0 + law.cfm));
  s.d -= h * s.v;
  return s.v - v_free;
}

double normal_step(const RelativeCfm& law, double g, double h, NormalState& s) {
  return contact_step(law, s.v - g * h, h, s);
}

double steady_sink(const RelativeCfm& law, double g, double h) {
  return law.cfm == 0.0 ? 0.0 : law.cfm * g * h * h / law.erp;
}

std::string describe(const RelativeCfm& law) {
  if (law.cfm == 0.0) return "none";
  return printf_string("constraint force mixing %g of each diagonal entry, error reduction %g",
                       law.cfm, law.erp) +
         (std::isfinite(law.max_push) ? printf_string(", push-out capped at %g m/s", law.max_push)
                                      : "");
}

}  // namespace dropcheck
