#include "harness/core/stack_law.hpp"

#include <cmath>

#include "harness/core/number_format.hpp"

namespace dropcheck {

double contact_sink(const StackLaw& law, double weight, double m_above, double m_below, double h) {
  const double inverse_mass = 1.0 / m_above + (m_below > 0.0 ? 1.0 / m_below : 0.0);
  const double tau = law.tau_steps * h;
  return law.compliance * h * weight / law.points + law.soft * tau * tau * weight * inverse_mass;
}

double sweep_residual(const StackLaw& law, double load, double m) {
  if (law.iterations <= 0) return 0.0;
  return std::pow(load / (load + m), law.iterations);
}

std::string describe(const StackLaw& law) {
  std::string text;
  auto add = [&](const std::string& part) { text += (text.empty() ? "" : ", ") + part; };
  if (law.compliance > 0.0)
    add(printf_string("each contact sinks %.3g*h*W/%d (CFM/ERP)", law.compliance, law.points));
  if (law.soft > 0.0)
    add(printf_string("a soft contact sags %.3g*(%gh)^2*W*(1/m_a + 1/m_b)", law.soft,
                      law.tau_steps));
  if (law.iterations > 0) add(printf_string("%d solver sweeps a step", law.iterations));
  return text.empty() ? "rigid, converged every step" : text;
}

}  // namespace dropcheck
