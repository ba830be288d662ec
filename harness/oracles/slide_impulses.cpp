#include "harness/oracles/slide_impulses.hpp"

#include <algorithm>
#include <cmath>

namespace dropcheck {

std::vector<SlideImpulse> slide_impulses(std::span<const BodyState> states, const SlideSetup& s,
                                         double h) {
  // Gravity per unit mass: -g into the floor, the pull along the slip.
  const Vec3 gravity = s.pull * s.direction - s.g * Vec3::UnitY();
  std::vector<SlideImpulse> out;
  for (std::size_t n = 1; n < states.size(); ++n) {
    const Vec3 v0 = states[n - 1].velocity, v1 = states[n].velocity;
    const Vec3 j = v1 - v0 - h * gravity;
    const Vec3 tangent(j.x(), 0.0, j.z());
    // The slip friction must cancel: the step-start slip plus the pull's h*pull, along the
    // slide's direction (a slide's slip stays on it); friction opposes it, also on the step a
    // slide launched against its pull turns back.
    const double free_along = Vec3(v0.x(), 0.0, v0.z()).dot(s.direction) + s.pull * h;
    const Vec3 slip_dir = free_along >= 0.0 ? s.direction : Vec3(-s.direction);
    SlideImpulse k;
    k.normal = j.y();
    k.along = tangent.dot(slip_dir);
    k.across = (tangent - k.along * slip_dir).norm();
    k.needed = std::abs(free_along);
    k.slip = Vec3(v1.x(), 0.0, v1.z()).norm();
    k.speeds = v0.norm() + v1.norm();
    out.push_back(k);
  }
  return out;
}

SlidePath coulomb_path(std::span<const SlideImpulse> steps, const SlideSetup& s, double mu,
                       double h) {
  SlidePath p{{0.0}, {s.v0}, {0.0}};
  double x = 0.0, v = s.v0;
  for (const SlideImpulse& k : steps) {
    const double grip = mu * std::max(k.normal, 0.0);
    const double v_free = v + s.pull * h;
    v = std::abs(v_free) <= grip ? 0.0 : v_free - std::copysign(grip, v_free);
    x += h * v;
    p.s.push_back(x);
    p.v.push_back(v);
    p.off.push_back(0.0);
  }
  return p;
}

CoulombCertificate coulomb_certificate(std::span<const SlideImpulse> steps, double mu, double g,
                                       double h, double median_bound, double epsilon) {
  const bool strict = median_bound <= 0.0;
  std::int64_t first_slipping = -1;
  CoulombCertificate c;
  const double weight = g * h;  // the normal impulse of a body at rest, per unit mass
  const auto bad = [&c](std::int64_t n) {
    if (c.first_bad < 0) c.first_bad = n;
  };
  double friction_sum = 0.0, grip_sum = 0.0;
  std::vector<double> ratios;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const SlideImpulse& k = steps[i];
    const auto n = static_cast<std::int64_t>(i + 1);
    const double nw = k.normal / weight;
    c.min_normal = i == 0 ? nw : std::min(c.min_normal, nw);
    c.max_normal = i == 0 ? nw : std::max(c.max_normal, nw);
    // Rounding: relative in double; in float the speeds' own rounding, 16 epsilon of them.
    const double rounding =
        std::max(kCoulombRounding * weight, 16.0 * epsilon * (k.speeds + weight));
    const double relative = rounding / weight;
    if (k.normal < -rounding) {
      if (c.pull_step < 0) c.pull_step = n;
      bad(n);
      continue;
    }
    const double grip = mu * std::max(k.normal, 0.0);
    const double friction = std::hypot(k.along, k.across);
    // A step off the floor (N within rounding of 0) has no grip, and no friction beyond rounding.
    const double floor_rounding = rounding;
    const double over = grip > floor_rounding       ? friction / grip - 1.0
                        : friction > floor_rounding ? INFINITY
                                                    : 0.0;
    if (over > c.worst_over) c.worst_over = over, c.worst_over_step = n;
    const bool is_over = over > relative;
    if (is_over) {
      ++c.stale;
      if (strict) bad(n);
    }
    if (k.needed > grip * (1.0 + relative)) {
      ++c.slipping;
      if (first_slipping < 0) first_slipping = n;
      friction_sum -= k.along;
      grip_sum += grip;
      if (grip > 0.0) ratios.push_back(-k.along / grip);
      // Against the slip, the whole grip: -along = grip, to the bounds.
      const double short_by = grip > 0.0 ? 1.0 + k.along / grip : 0.0;
      if (short_by > c.worst_short) c.worst_short = short_by, c.worst_short_step = n;
      if (short_by <= relative && !is_over)
        ++c.exact;
      else if (strict)
        bad(n);
    } else {
      ++c.held;
      if (k.slip > c.creep) c.creep = k.slip, c.creep_step = n;
    }
  }
  if (grip_sum > 0.0) c.mean_ratio = friction_sum / grip_sum;
  if (!ratios.empty()) {
    std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
    c.median_ratio = ratios[ratios.size() / 2];
  }
  if (!strict && !(std::abs(c.median_ratio - 1.0) <= median_bound)) bad(first_slipping);
  c.holds = c.first_bad < 0;
  return c;
}

}  // namespace dropcheck
