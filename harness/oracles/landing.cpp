#include "harness/oracles/landing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <variant>

#include "harness/oracles/contact_laws.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/oracles/replayed_contact.hpp"

namespace dropcheck {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Static box `f` (a box: a sphere is no floor) holds body `b`: f's top is at or below b's bottom
// and b's centre lies over f's footprint in the x-z plane.
bool holds(const Body& f, const Body& b) {
  return f.is_static && f.shape == Shape::box && top_of(f) <= bottom_of(b) &&
         std::abs(b.position.x() - f.position.x()) <= f.half_extents.x() &&
         std::abs(b.position.z() - f.position.z()) <= f.half_extents.z();
}

// The highest static box holding body i; -1 when there is none.
long floor_under(const Scene& scene, std::size_t i) {
  long best = -1;
  for (std::size_t j = 0; j < scene.bodies.size(); ++j) {
    if (!holds(scene.bodies[j], scene.bodies[i])) continue;
    if (best < 0 || top_of(scene.bodies[j]) > top_of(scene.bodies[static_cast<std::size_t>(best)]))
      best = static_cast<long>(j);
  }
  return best;
}

// Body `o` shares dynamic body `b`'s x-z footprint (open rectangles overlap: boxes that only
// touch at an edge do not stack) and reaches above the floor top `floor_top`: a dynamic body
// stacked with b, or a static one (not b's floor) in its way.
bool stacked_with(const Body& b, const Body& o, double floor_top) {
  return top_of(o) > floor_top &&
         std::abs(b.position.x() - o.position.x()) < b.half_extents.x() + o.half_extents.x() &&
         std::abs(b.position.z() - o.position.z()) < b.half_extents.z() + o.half_extents.z();
}

// Vertical acceleration of body i without damping: a = g_y + sum(F_y)/m over its constant forces.
// NaN when a spring acts on it (its force depends on the state: no closed form here).
double vertical_acceleration(const Scene& scene, std::size_t i) {
  double f = 0.0;
  for (const Force& force : scene.forces) {
    if (std::find(force.bodies.begin(), force.bodies.end(), i) == force.bodies.end()) continue;
    if (std::holds_alternative<Spring>(force.law)) return kNaN;
    f += std::get<ConstantForce>(force.law).force.y();
  }
  return scene.world.gravity.y() + f / scene.bodies[i].mass;
}

// Smallest positive root of A*t^2 + B*t + C = 0 with C > 0; NaN when there is none.
// Stable form (no cancellation): q = -(B + sign(B)*sqrt(B^2 - 4AC))/2, roots q/A and C/q.
double first_positive_root(double A, double B, double C) {
  if (A == 0.0) return B < 0.0 ? -C / B : kNaN;
  const double d = B * B - 4.0 * A * C;
  if (d < 0.0) return kNaN;
  const double q = -0.5 * (B + std::copysign(std::sqrt(d), B));
  double best = kNaN;
  for (const double r : {q / A, C / q})
    if (r > 0.0 && !(r >= best)) best = r;
  return best;
}

// (t - (1 - exp(-k*t))/k)/k, the drift of the damped fall. It cancels for small k*t, where the
// Taylor series of exp gives t^2/2 - k*t^3/6 + k^2*t^4/24 - k^3*t^5/120 (next term (k*t)^4/360
// relative: below 3e-15 for k*t < 1e-3).
double drift(double k, double t) {
  const double kt = k * t;
  if (std::abs(kt) < 1e-3) return t * t * (0.5 - kt / 6.0 + kt * kt / 24.0 - kt * kt * kt / 120.0);
  return (t + std::expm1(-kt) / k) / k;
}

// End of an interval [0, t] over which y(t) - target changes sign once; NaN when y never reaches
// target. v(t) is monotone (dv/dt = (a - k*v0)*exp(-k*t) keeps its sign), so y has at most one
// extremum. a <= 0: y eventually falls, double t until y(t) <= target. a > 0: y only comes down
// while v < 0; its lowest point is where v(t) = 0: exp(-k*t) = a/(a - k*v0), t = log1p(-k*v0/a)/k.
double bracket_end(double y0, double v0, double a, double k, double target) {
  if (a > 0.0) {
    if (v0 >= 0.0) return kNaN;
    const double t_low = std::log1p(-k * v0 / a) / k;
    return height_continuous(y0, v0, a, k, t_low) <= target ? t_low : kNaN;
  }
  double t = 1.0;
  for (int i = 0; i < 64; ++i, t *= 2.0)
    if (height_continuous(y0, v0, a, k, t) <= target) return t;
  return kNaN;
}

}  // namespace

StillFigures still_figures(const Trajectory& run, std::size_t body, std::int64_t from) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  StillFigures f;
  for (std::size_t s = 0; s < run.samples(); ++s) {
    if (run.recorded[s] < from) continue;
    const BodyState& b = run.at(s, body);
    f.speed = std::max(f.speed, b.velocity.norm());
    lo = lo.cwiseMin(b.position);
    hi = hi.cwiseMax(b.position);
  }
  f.range = (hi - lo).maxCoeff();
  return f;
}

// Model: dv/dt = a - k*v, v(0) = v0, y(0) = y0.
// Solution (k > 0): v(t) = a/k + (v0 - a/k)*exp(-k*t)
//   y(t) = y0 + v0*(1 - exp(-k*t))/k + a*(t - (1 - exp(-k*t))/k)/k
// k = 0 (the limit): y(t) = y0 + v0*t + a*t^2/2.
double height_continuous(double y0, double v0, double a, double k, double t) {
  if (k == 0.0) return y0 + v0 * t + 0.5 * a * t * t;
  return y0 + v0 * (-std::expm1(-k * t) / k) + a * drift(k, t);
}

// k = 0: the parabola's first positive root (a/2)*t^2 + v0*t + (y0 - target) = 0, closed form.
// k > 0: transcendental; bisection of y(t) - target on a bracket holding only the first crossing,
// to the last bit of the double.
double contact_time_continuous(double y0, double v0, double a, double k, double target) {
  if (y0 <= target) return 0.0;
  if (k == 0.0) return first_positive_root(0.5 * a, v0, y0 - target);
  double lo = 0.0, hi = bracket_end(y0, v0, a, k, target);
  if (std::isnan(hi)) return kNaN;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (height_continuous(y0, v0, a, k, mid) > target ? lo : hi) = mid;
  }
  return hi;
}

std::vector<LandingSetup> landing_setups(const Scene& scene) {
  std::vector<LandingSetup> out;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Body& b = scene.bodies[i];
    const long f = b.is_static ? -1 : floor_under(scene, i);
    if (f < 0) continue;
    LandingSetup s{.body = i, .floor = static_cast<std::size_t>(f)};
    s.floor_top = top_of(scene.bodies[s.floor]);
    s.floor_bottom = bottom_of(scene.bodies[s.floor]);
    s.half_height = b.half_extents.y();
    s.rest_height = s.floor_top + s.half_height;
    s.weight = b.mass * scene.world.gravity.norm();
    s.contact_time =
        contact_time_continuous(b.position.y(), b.velocity.y(), vertical_acceleration(scene, i),
                                scene.world.damping_rate, s.rest_height);
    out.push_back(s);
  }
  return out;
}

std::string LandingExclusion::sentence(const Scene& scene) const {
  const std::string name = "'" + scene.bodies[body].name + "'";
  const std::string o = "'" + scene.bodies[other].name + "'";
  const std::string kind = scene.bodies[other].is_static ? "static body " : "dynamic body ";
  return name + " not judged: " + (on_other ? "lands on " + kind + o : kind + o + " lands on it") +
         " (the landing oracle covers one body over a static floor)";
}

std::vector<LandingExclusion> landing_exclusions(const Scene& scene) {
  std::vector<LandingExclusion> out;
  for (const LandingSetup& s : landing_setups(scene)) {
    const Body& b = scene.bodies[s.body];
    long below = -1, above = -1;  // nearest stacked body under / over b
    for (std::size_t j = 0; j < scene.bodies.size(); ++j) {
      const Body& o = scene.bodies[j];
      if (j == s.body || j == s.floor || !stacked_with(b, o, s.floor_top)) continue;
      if (o.is_static && o.position.y() >= b.position.y()) continue;  // only what b falls onto
      long& slot = o.position.y() < b.position.y() ? below : above;
      const auto nearer = [&](long k) {
        return k < 0 || std::abs(o.position.y() - b.position.y()) <
                            std::abs(scene.bodies[static_cast<std::size_t>(k)].position.y() -
                                     b.position.y());
      };
      if (nearer(slot)) slot = static_cast<long>(j);
    }
    if (below < 0 && above < 0) continue;
    out.push_back({s.body, static_cast<std::size_t>(below >= 0 ? below : above), below >= 0});
  }
  return out;
}

std::vector<LandingSetup> engine_landing_setups(const Scene& scene, const EngineInfo& info) {
  // Gravity with a part along the floor (an incline): a body that lands slides on, as no landing
  // closed form says; only the slides are judged (slide_setups).
  if (scene.world.gravity.x() != 0.0 || scene.world.gravity.z() != 0.0) return {};
  const std::vector<LandingExclusion> excluded = landing_exclusions(scene);
  // Bodies with a contact law of their own: bounces and slides.
  std::vector<std::size_t> own_law;
  for (const BounceSetup& b : bounce_setups(scene)) own_law.push_back(b.body);
  for (const SlideSetup& s : slide_setups(scene)) own_law.push_back(s.body);
  std::vector<LandingSetup> setups;
  for (LandingSetup setup : landing_setups(scene)) {
    if (std::any_of(excluded.begin(), excluded.end(),
                    [&](const LandingExclusion& e) { return e.body == setup.body; }) ||
        std::find(own_law.begin(), own_law.end(), setup.body) != own_law.end())
      continue;
    setup.floor_top += std::max(0.0, info.rest_offset + info.rest_tolerance);
    setups.push_back(setup);
  }
  return setups;
}

std::string Tunnelling::sentence() const {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "tunnels: it travels %.3g m per step at contact, more than the floor (%.3g m) plus "
                "its height (%.3g m)",
                travel, floor_thickness, height);
  return buf;
}

// The slab an end-of-step centre must fall in for the body to overlap the floor at a step end:
// [floor bottom - half height, floor top + half height] (geometric floor, no engine skin).
Tunnelling discrete_tunnelling(Law law, const Scene& scene, double h, const LandingSetup& setup) {
  Tunnelling t;
  const Body& floor = scene.bodies[setup.floor];
  const double slab_top = top_of(floor) + setup.half_height;
  const double slab_bottom = bottom_of(floor) - setup.half_height;
  t.floor_thickness = top_of(floor) - bottom_of(floor);
  t.height = 2.0 * setup.half_height;
  const Trajectory law_run = predict_discrete(law, scene, h);
  for (std::size_t s = 0; s < law_run.samples(); ++s) {
    const double y = law_run.at(s, setup.body).position.y();
    if (y > slab_top) continue;
    t.step = law_run.recorded[s];
    t.tunnels = y < slab_bottom;
    if (s > 0) t.travel = law_run.at(s - 1, setup.body).position.y() - y;
    break;
  }
  return t;
}

bool ends_below_floor(const Trajectory& run, const LandingSetup& setup) {
  return run.samples() > 0 &&
         run.final_state(setup.body).position.y() < setup.floor_bottom - setup.half_height;
}

TunnelVerdict judge_tunnelling(const Tunnelling& law, const EngineInfo& info, const Trajectory& run,
                               const LandingSetup& setup) {
  if (!law.tunnels || !ends_below_floor(run, setup)) return TunnelVerdict::none;
  return info.continuous_collision ? TunnelVerdict::fault : TunnelVerdict::limit;
}

std::int64_t first_contact_step(const Trajectory& run, const LandingSetup& setup) {
  for (std::size_t s = 0; s < run.samples(); ++s)
    if (run.at(s, setup.body).position.y() - setup.half_height <= setup.floor_top)
      return run.recorded[s];
  return -1;
}

std::int64_t discrete_contact_step(Law law, const Scene& scene, double h,
                                   const LandingSetup& setup) {
  return first_contact_step(predict_discrete(law, scene, h), setup);
}

LandingObservation observe_landing(const Trajectory& run, const LandingSetup& setup,
                                   const StillCriteria& still) {
  LandingObservation o{.first_contact_time = kNaN,
                       .deepest = kNaN,
                       .rebound = kNaN,
                       .rest_offset = kNaN,
                       .still_speed = kNaN,
                       .still_range = kNaN,
                       .after_contact = kNaN};
  if (run.samples() == 0) return o;
  o.first_contact_step = first_contact_step(run, setup);
  double lowest = INFINITY, highest_after = -INFINITY;
  for (std::size_t s = 0; s < run.samples(); ++s) {
    const double y = run.at(s, setup.body).position.y();
    lowest = std::min(lowest, y);
    if (o.first_contact_step >= 0 && run.recorded[s] >= o.first_contact_step)
      highest_after = std::max(highest_after, y);
  }
  o.deepest = lowest - setup.rest_height;
  o.rest_offset = run.final_state(setup.body).position.y() - setup.rest_height;
  const std::int64_t window_start = run.recorded.back() - std::llround(still.seconds / run.h);
  const StillFigures still_then = still_figures(run, setup.body, window_start);
  o.still_speed = still_then.speed;
  o.still_range = still_then.range;
  if (o.first_contact_step < 0) return o;
  o.first_contact_time = static_cast<double>(o.first_contact_step) * run.h;
  o.rebound = highest_after - setup.rest_height;
  o.after_contact = static_cast<double>(run.recorded.back() - o.first_contact_step) * run.h;
  o.still_judged = o.first_contact_step <= window_start;
  o.still = o.still_judged && o.still_speed <= still.max_speed && o.still_range <= still.max_range;
  return o;
}

std::optional<ClimbPath> climb_path(const EngineInfo& info, const Scene& scene, double h,
                                    const LandingSetup& setup) {
  const RelativeCfm& law = info.relative_cfm;
  const Law free = info.law;
  if (law.cfm == 0.0 || !std::isfinite(law.max_push) || free.scheme != Scheme::Euler ||
      free.position != PositionUpdate::SemiImplicit ||
      free.damping == DampingOrder::AfterPosition || pushed(scene, setup.body))
    return std::nullopt;
  const Trajectory fall = predict_discrete(free, scene, h);
  const std::int64_t contact = first_contact_step(fall, setup);
  ClimbPath path;
  for (std::size_t n = 0; n < fall.samples(); ++n) {
    path.y.push_back(fall.at(n, setup.body).position.y());
    path.climb = fall.at(n, setup.body).velocity.y();
    if (fall.recorded[n] == contact) break;
  }
  if (contact < 0) return path;
  const double phi = std::exp(-scene.world.damping_rate * h);
  const double a = scene.world.gravity.y();
  NormalState s{path.climb, setup.rest_height - path.y.back()};
  for (std::int64_t n = contact + 1; n <= step_count(scene, h); ++n) {
    double x = 0.0, v_free = s.v;
    advance(free, phi, h, a, x, v_free);
    if (s.d >= 0.0) {
      contact_step(law, v_free, h, s);
    } else {
      s.v = v_free;
      s.d -= h * s.v;
    }
    path.y.push_back(setup.rest_height - s.d);
  }
  path.climb = s.v;
  return path;
}

std::optional<ClimbPath> replayed_landing_path(const EngineInfo& info, const Scene& scene, double h,
                                               const LandingSetup& setup) {
  if (info.contact_solver.kind != ContactSolverKind::hunt_crossley) return std::nullopt;
  try {
    const std::vector<BodyState> states =
        replayed_states(scene, setup.body, info.contact_solver, h, step_count(scene, h));
    ClimbPath path;
    for (const BodyState& s : states) path.y.push_back(s.position.y());
    path.climb = states.back().velocity.y();
    path.replayed = describe(info.contact_solver);
    return path;
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
}

double off_climb(const Trajectory& run, const LandingSetup& setup, const ClimbPath& path) {
  double worst = 0.0;
  for (std::size_t n = 0; n < run.samples(); ++n) {
    const auto k = static_cast<std::size_t>(run.recorded[n]);
    if (k >= path.y.size()) break;
    worst = std::max(worst, std::abs(run.at(n, setup.body).position.y() - path.y[k]));
  }
  return worst;
}

}  // namespace dropcheck
