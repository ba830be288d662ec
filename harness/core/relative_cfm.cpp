#include "harness/core/relative_cfm.hpp"

#include "harness/core/number_format.hpp"

namespace dropcheck {

double normal_step(const RelativeCfm& law, double g, double h, NormalState& s) {
  if (law.cfm == 0.0) return g * h;  // rigid: the contact cancels the approach, nothing sinks
  const double approach = s.v - g * h;
  s.v = (law.cfm * approach + law.erp * s.d / h) / (1.0 + law.cfm);
  s.d -= h * s.v;
  return s.v - approach;
}

double steady_sink(const RelativeCfm& law, double g, double h) {
  return law.cfm == 0.0 ? 0.0 : law.cfm * g * h * h / law.erp;
}

std::string describe(const RelativeCfm& law) {
  if (law.cfm == 0.0) return "none";
  return printf_string("constraint force mixing %g of each diagonal entry, error reduction %g",
                       law.cfm, law.erp);
}

}  // namespace dropcheck
