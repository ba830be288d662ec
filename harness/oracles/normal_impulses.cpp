#include "harness/oracles/normal_impulses.hpp"

#include <algorithm>
#include <cmath>

namespace dropcheck {

NormalCertificate normal_certificate(std::span<const BodyState> states, double bottom_offset,
                                     double floor_top, double g, double h, double epsilon,
                                     double min_approach) {
  NormalCertificate c;
  const double weight = g * h;       // N of a body at rest, per unit mass
  double approach = 0.0, out = 0.0;  // the current impact's
  std::int64_t began = -1;
  const auto close_impact = [&] {
    if (began > 0 && approach >= min_approach && out / approach > c.rebound)
      c.rebound = out / approach, c.rebound_step = began;
    began = -1;
  };
  for (std::size_t k = 1; k < states.size(); ++k) {
    const auto n = static_cast<std::int64_t>(k);
    const double v0 = states[k - 1].velocity.y(), v1 = states[k].velocity.y();
    const double normal = v1 - v0 + weight;
    const double rounding = 16.0 * epsilon * (std::abs(v0) + std::abs(v1) + weight);
    const double after = states[k].position.y() - bottom_offset - floor_top;
    const double gap = std::min(after, states[k - 1].position.y() - bottom_offset - floor_top);
    if (-after > c.deepest) c.deepest = -after, c.deepest_step = n;
    if (normal < -rounding) {
      if (c.pull_step < 0) c.pull_step = n;
      c.worst_pull = std::min(c.worst_pull, normal / weight);
    }
    if (normal <= rounding) {
      close_impact();
      continue;
    }
    ++c.contact_steps;
    if (gap > c.widest_gap) c.widest_gap = gap, c.widest_gap_step = n;
    if (began < 0) {
      began = n;
      approach = -(v0 - weight);  // the free fall's speed at the step's end, downward positive
      out = 0.0;
    }
    out = std::max(out, v1);
  }
  close_impact();
  return c;
}

}  // namespace dropcheck
