#include "harness/oracles/contact_laws.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "harness/oracles/landing.hpp"

namespace dropcheck {
namespace {

// One axis of the discrete clamp law: v <- max(v - a*h, 0), x += h*v from v0. The velocity is 0
// after step N = ceil(v0/(a*h)); the distance is h*sum_{n=1}^{N} (v0 - n*a*h), the last term
// clamped at 0: h*((N - 1)*v0 - a*h*(N - 1)*N/2).
struct AxisStop {
  std::int64_t steps = 0;
  double distance = 0.0;
};

AxisStop clamp_axis(double v0, double a, double h) {
  if (v0 <= 0.0) return {};
  const double dv = a * h;
  const auto n = static_cast<std::int64_t>(std::ceil(v0 / dv));
  const double moving = static_cast<double>(n - 1);  // steps that end with v > 0
  return {n, h * (moving * v0 - dv * moving * (moving + 1.0) / 2.0)};
}

// What every contact law here assumes: contacts on, gravity straight down (-y), nothing turning.
bool level_contact(const Scene& scene) {
  const Vec3& g = scene.world.gravity;
  return scene.world.contacts && g.x() == 0.0 && g.z() == 0.0 && g.y() < 0.0 &&
         !needs_rotation(scene);
}

// A force of the scene acts on body i.
bool pushed(const Scene& scene, std::size_t i) {
  for (const Force& f : scene.forces)
    for (std::size_t k : f.bodies)
      if (k == i) return true;
  return false;
}

}  // namespace

SlideStop slide_to_stop(double v0, double mu, double g, double h, FrictionModel model,
                        double angle) {
  if (!(v0 >= 0.0 && mu > 0.0 && g > 0.0 && h > 0.0))
    throw std::invalid_argument("slide_to_stop: needs v0 >= 0, mu > 0, g > 0, h > 0");
  const double diagonal = std::numbers::pi / 4.0;
  const bool along_axis = angle == 0.0, at_diagonal = std::abs(angle - diagonal) < 1e-12;
  if (model != FrictionModel::cone && !along_axis && !at_diagonal)
    throw std::invalid_argument("slide_to_stop: a pyramid is exact at angles 0 and pi/4 only");
  // Per-axis deceleration: the cone and every model along an axis decelerate the slip by mu*g.
  // At pi/4 each axis slides at v0/sqrt(2); the box pyramid stops each at mu*g (sqrt(2)*mu*g
  // along the slip), the sum pyramid shares mu*N between them (mu*g/2 each, mu*g/sqrt(2)).
  double axis_v = v0, axis_a = mu * g;
  int axes = 1;
  if (model != FrictionModel::cone && at_diagonal) {
    axis_v = v0 / std::sqrt(2.0);
    axis_a = model == FrictionModel::box_pyramid ? mu * g : mu * g / 2.0;
    axes = 2;
  }
  SlideStop s;
  s.deceleration = axes == 2 ? std::sqrt(2.0) * axis_a : axis_a;
  s.stop_time = v0 / s.deceleration;
  s.distance = v0 * v0 / (2.0 * s.deceleration);
  const AxisStop a = clamp_axis(axis_v, axis_a, h);
  s.stop_step = a.steps;
  s.step_distance = axes == 2 ? std::sqrt(2.0) * a.distance : a.distance;
  return s;
}

std::vector<SlideSetup> slide_setups(const Scene& scene) {
  std::vector<SlideSetup> out;
  const Material m = scene_material(scene);
  const Vec3& g = scene.world.gravity;
  if (!level_contact(scene) || !m.friction || *m.friction <= 0.0) return out;
  // The floor under each body is the landing oracle's (the highest static box holding it).
  for (const LandingSetup& l : landing_setups(scene)) {
    const std::size_t i = l.body;
    const Body& b = scene.bodies[i];
    if (b.shape != Shape::box || b.velocity.y() != 0.0) continue;
    if (std::abs(b.position.y() - l.rest_height) > 1e-9) continue;  // not resting on it
    const double speed = std::hypot(b.velocity.x(), b.velocity.z());
    if (speed == 0.0) continue;
    if (pushed(scene, i)) continue;
    double angle = std::atan2(std::abs(b.velocity.z()), std::abs(b.velocity.x()));
    if (angle > std::numbers::pi / 4.0) angle = std::numbers::pi / 2.0 - angle;
    out.push_back({i, speed, angle, *m.friction, -g.y()});
  }
  return out;
}

SlideObservation observe_slide(const Trajectory& run, const SlideSetup& setup,
                               double stopped_speed) {
  SlideObservation o;
  if (run.samples() == 0) return o;
  const Vec3 start = run.at(0, setup.body).position;
  for (std::size_t s = 0; s < run.samples(); ++s) {
    const BodyState& b = run.at(s, setup.body);
    o.distance = std::hypot(b.position.x() - start.x(), b.position.z() - start.z());
    if (std::hypot(b.velocity.x(), b.velocity.z()) <= stopped_speed) {
      o.stop_step = run.recorded[s];
      return o;
    }
  }
  return o;
}

namespace {

// One sphere over a floor under a bounce law (harness/core/bounce_law.hpp), a step at a time:
// contacts found where the last step ended.
class BounceStepper {
 public:
  BounceStepper(const BounceLaw& law, double h0, double e, double g, double h, double size)
      : law_(law),
        e_(e),
        g_(g),
        h_(h),
        reach_(law.contact_distance + law.contact_distance_per_size * size),
        gap_(h0) {}

  void step() {
    const double v_free = v_ - g_ * h_;
    double moved = 0.0;  // a push in position
    if (gap_ < reach_ || gap_ < 0.0) {
      const double rest = -v_ > law_.threshold ? e_ * -v_ : 0.0;
      double target = rest - gap_ / h_;  // speculative: the gap may close this step
      if (gap_ < 0.0) {
        const double push = std::min(law_.erp * -gap_ / h_, law_.max_push);
        target = law_.push_in_position ? rest : std::max(push, rest);
        if (law_.push_in_position) moved = h_ * push;
      }
      v_ = std::max(v_free, target);
    } else {
      v_ = v_free;
    }
    gap_ += h_ * v_ + moved;
  }
  double gap() const { return gap_; }
  double v() const { return v_; }

 private:
  BounceLaw law_;
  double e_, g_, h_, reach_;
  double gap_, v_ = 0.0;
};

// What a path shows, read a step at a time (observe_bounce).
class BounceWatch {
 public:
  BounceWatch(double g, double h, int bounces) : gh_(g * h), bounces_(bounces) {}

  // The state after step n (n = 0, 1, ... in order); true once `bounces` apexes are seen.
  bool add(std::int64_t n, double gap, double v) {
    if (n > 0 && o_.contact_step < 0 && v > v_ - gh_ + 1e-3 * gh_) {
      // The floor pushed in step n: the impact is the step before (it ended in, or speculatively
      // near, the floor).
      o_.contact_step = n - 1;
      o_.speed_in = -v_;
      o_.speed_out = v;
    } else if (o_.contact_step >= 0 && v_ > 0.0 && v <= 0.0) {
      o_.apexes.push_back(gap_);
    }
    gap_ = gap;
    v_ = v;
    return static_cast<int>(o_.apexes.size()) >= bounces_;
  }
  const BounceObservation& result() const { return o_; }

 private:
  double gh_;
  int bounces_;
  double gap_ = 0.0, v_ = 0.0;
  BounceObservation o_;
};

}  // namespace

BouncePath bounce_path(const BounceLaw& law, double h0, double e, double g, double h,
                       std::int64_t steps, double size) {
  BouncePath p;
  p.gap.reserve(static_cast<std::size_t>(steps) + 1);
  p.v.reserve(static_cast<std::size_t>(steps) + 1);
  BounceStepper sphere(law, h0, e, g, h, size);
  p.gap.push_back(sphere.gap());
  p.v.push_back(sphere.v());
  for (std::int64_t n = 1; n <= steps; ++n) {
    sphere.step();
    p.gap.push_back(sphere.gap());
    p.v.push_back(sphere.v());
  }
  return p;
}

BounceObservation observe_bounce(const std::vector<double>& gap, const std::vector<double>& v,
                                 double g, double h, int bounces) {
  BounceWatch watch(g, h, bounces);
  const std::size_t n = std::min(gap.size(), v.size());
  for (std::size_t i = 0; i < n; ++i)
    if (watch.add(static_cast<std::int64_t>(i), gap[i], v[i])) break;
  return watch.result();
}

Bounce bounce(double h0, double e, double g, double h, int bounces) {
  if (!(h0 > 0.0 && g > 0.0 && h > 0.0 && e >= 0.0 && e <= 1.0))
    throw std::invalid_argument("bounce: needs h0 > 0, g > 0, h > 0, 0 <= e <= 1");
  Bounce b;
  b.impact_speed = std::sqrt(2.0 * g * h0);
  const double fall = std::sqrt(2.0 * h0 / g);
  for (int n = 1; n <= bounces; ++n) {
    b.apexes.push_back(std::pow(e, 2 * n) * h0);
    b.flights.push_back(2.0 * std::pow(e, n) * fall);
  }
  b.time_to_rest = e < 1.0 ? fall * (1.0 + e) / (1.0 - e) : INFINITY;
  // The ideal law, streamed until the apex after the first impact. The fall takes about fall/h
  // steps and the climb no more than the fall, so three falls and a few steps bound it.
  const double bound = 3.0 * fall / h + 8.0;
  if (!(bound < 1e10)) throw std::invalid_argument("bounce: over 1e10 steps to its first apex");
  BounceStepper sphere(kIdealBounce, h0, e, g, h, 0.0);
  BounceWatch watch(g, h, 1);
  watch.add(0, sphere.gap(), sphere.v());
  for (std::int64_t n = 1; n <= static_cast<std::int64_t>(bound); ++n) {
    sphere.step();
    if (watch.add(n, sphere.gap(), sphere.v())) break;
  }
  const BounceObservation& o = watch.result();
  b.contact_step = o.contact_step;
  b.step_speed_in = o.speed_in;
  b.step_speed_out = o.speed_out;
  b.step_apex = o.apexes.empty() ? 0.0 : o.apexes.front();
  return b;
}

std::vector<BounceSetup> bounce_setups(const Scene& scene) {
  std::vector<BounceSetup> out;
  const Material m = scene_material(scene);
  const Vec3& g = scene.world.gravity;
  if (!level_contact(scene) || !m.restitution || scene.world.damping_rate != 0.0) return out;
  const std::vector<LandingExclusion> stacked = landing_exclusions(scene);
  for (const LandingSetup& l : landing_setups(scene)) {
    const Body& b = scene.bodies[l.body];
    if (std::any_of(stacked.begin(), stacked.end(),
                    [&](const LandingExclusion& x) { return x.body == l.body; }))
      continue;  // on or under another body, or over a static one: no floor bounce
    if (b.shape != Shape::sphere || b.velocity != Vec3::Zero()) continue;
    const double h0 = b.position.y() - b.radius - l.floor_top;
    if (!(h0 > 0.0)) continue;
    if (pushed(scene, l.body)) continue;
    const double size = std::min(b.half_extents.norm(), scene.bodies[l.floor].half_extents.norm());
    out.push_back({l.body, h0, *m.restitution, -g.y(), b.radius, l.floor_top, size});
  }
  return out;
}

BouncePath observed_path(const Trajectory& run, const BounceSetup& setup) {
  BouncePath p;
  for (std::size_t s = 0; s < run.samples(); ++s) {
    const BodyState& b = run.at(s, setup.body);
    p.gap.push_back(b.position.y() - setup.radius - setup.floor_top);
    p.v.push_back(b.velocity.y());
  }
  return p;
}

}  // namespace dropcheck
