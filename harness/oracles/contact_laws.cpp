#include "harness/oracles/contact_laws.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "harness/oracles/landing.hpp"

namespace dropcheck {

bool floor_contact(const Scene& scene) {
  return scene.world.contacts && scene.world.gravity.y() < 0.0 && !needs_rotation(scene);
}

bool level_gravity(const Scene& scene) {
  return scene.world.gravity.x() == 0.0 && scene.world.gravity.z() == 0.0;
}

bool exact_slide_angle(FrictionModel model, double angle) {
  return model == FrictionModel::cone || angle == 0.0 ||
         std::abs(angle - std::numbers::pi / 4.0) < 1e-12;
}

double slide_grip(double mu, double g, FrictionModel model, double angle) {
  if (!exact_slide_angle(model, angle))
    throw std::invalid_argument("slide: a pyramid is exact at angles 0 and pi/4 only");
  if (model == FrictionModel::cone || angle == 0.0) return mu * g;
  return model == FrictionModel::box_pyramid ? std::sqrt(2.0) * mu * g : mu * g / std::sqrt(2.0);
}

SlideStop slide_to_stop(double v0, double mu, double g, double h, FrictionModel model, double angle,
                        double pull) {
  if (!(v0 >= 0.0 && mu > 0.0 && g > 0.0 && h > 0.0))
    throw std::invalid_argument("slide_to_stop: needs v0 >= 0, mu > 0, g > 0, h > 0");
  const double grip = slide_grip(mu, g, model, angle);
  SlideStop s;
  s.deceleration = grip - pull;
  s.stops = std::abs(pull) <= grip && (v0 == 0.0 || s.deceleration > 0.0);
  if (!s.stops || v0 == 0.0) {
    s.stop_step = s.stops ? 0 : -1;
    return s;
  }
  s.stop_time = v0 / s.deceleration;
  s.distance = v0 * v0 / (2.0 * s.deceleration);
  // v_n = v0 - n*a*h while positive: zero after N = ceil(v0/(a*h)) steps; the distance is
  // h*sum_{n=1}^{N-1} (v0 - n*a*h) = h*((N - 1)*v0 - a*h*(N - 1)*N/2).
  const double dv = s.deceleration * h;
  s.stop_step = static_cast<std::int64_t>(std::ceil(v0 / dv));
  const double moving = static_cast<double>(s.stop_step - 1);  // steps that end with v > 0
  s.step_distance = h * (moving * v0 - dv * moving * (moving + 1.0) / 2.0);
  return s;
}

double slide_distance_continuous(double v0, double pull, double grip, double t) {
  double d = 0.0;
  if (v0 > 0.0) {
    const double a = grip - pull;
    if (a <= 0.0 || t <= v0 / a) return v0 * t - 0.5 * a * t * t;
    d = v0 * v0 / (2.0 * a);
    t -= v0 / a;
  }
  if (std::abs(pull) <= grip) return d;
  return d + std::copysign(0.5 * (std::abs(pull) - grip) * t * t, pull);
}

namespace {

// The farthest the slide goes from its start at the scene's step over its duration (m along the
// slip, either way): the ideal discrete law of every friction model exact at its angle.
double slide_reach(const SlideSetup& s, const Scene& scene) {
  const double h = scene.timestep.seconds;
  double reach = 0.0;
  for (FrictionModel m : kFrictionModels) {
    if (!exact_slide_angle(m, s.angle)) continue;
    for (const double d : slide_path(s, m, h, step_count(scene, h)).s)
      reach = std::max(reach, std::abs(d));
  }
  return reach;
}

}  // namespace

std::vector<SlideSetup> slide_setups(const Scene& scene) {
  std::vector<SlideSetup> out;
  const Material m = scene_material(scene);
  const Vec3& g = scene.world.gravity;
  if (!floor_contact(scene) || !m.friction || *m.friction <= 0.0 || scene.world.damping_rate != 0.0)
    return out;
  const Vec3 pull(g.x(), 0.0, g.z());
  const std::vector<LandingExclusion> stacked = landing_exclusions(scene);
  // The floor under each body is the landing oracle's (the highest static box holding it).
  for (const LandingSetup& l : landing_setups(scene)) {
    const std::size_t i = l.body;
    const Body& b = scene.bodies[i];
    if (b.shape != Shape::box || b.velocity.y() != 0.0) continue;
    if (std::any_of(stacked.begin(), stacked.end(),
                    [&](const LandingExclusion& x) { return x.body == i; }))
      continue;  // another body on or under it: its normal force is not m*g
    if (std::abs(b.position.y() - l.rest_height) > 1e-9) continue;  // not resting on it
    if (pushed(scene, i)) continue;
    const Vec3 launch(b.velocity.x(), 0.0, b.velocity.z());
    if (launch == Vec3::Zero() && pull == Vec3::Zero()) continue;  // at rest: nothing slides
    const Vec3 u = launch != Vec3::Zero() ? launch.normalized() : pull.normalized();
    if (pull.cross(u).norm() > 1e-12 * pull.norm()) continue;  // pulled across the slip
    double angle = std::atan2(std::abs(u.z()), std::abs(u.x()));
    if (angle > std::numbers::pi / 4.0) angle = std::numbers::pi / 2.0 - angle;
    const SlideSetup setup{i, launch.norm(), u, angle, *m.friction, -g.y(), pull.dot(u)};
    // It must stay over its floor: the end of its reach, either way, within the floor's top face.
    const Body& f = scene.bodies[l.floor];
    // (1 % more: a run at another step, as the stability search makes, goes a little farther.)
    const double reach = 1.01 * slide_reach(setup, scene);
    bool on_floor = true;
    for (const double sign : {1.0, -1.0}) {
      const Vec3 end = b.position + sign * reach * u;
      on_floor = on_floor && std::abs(end.x() - f.position.x()) <= f.half_extents.x() &&
                 std::abs(end.z() - f.position.z()) <= f.half_extents.z();
    }
    if (on_floor) out.push_back(setup);
  }
  return out;
}

namespace {

// One step of the clamp law from (s, v): the position moves with the new speed (semi-implicit) or
// with the step-start speed (explicit).
// One step of the clamp law, the friction taking at most grip_h off the slip; a step that stops
// the slip leaves `stick` of it.
void slide_step(const SlideSetup& setup, double grip_h, double stick, double h,
                PositionUpdate position, bool after_position, double& s, double& v) {
  const double v_start = v;
  const double v_free = v + setup.pull * h;
  v = std::abs(v_free) <= grip_h ? stick * v_free : v_free - std::copysign(grip_h, v_free);
  s += h * (after_position ? v_free : position == PositionUpdate::Explicit ? v_start : v);
}

// The normal side of the law over steps 0..steps: each step's grip*h, scaled by that step's normal
// impulse against a rigid contact's g*h (exactly 1 for a rigid law), and the sink below the height
// after step 1 (harness/core/relative_cfm.hpp).
struct NormalSide {
  std::vector<double> grip_h, off;
  double stick = 0.0;
};
NormalSide normal_side(const SlideSetup& setup, FrictionModel model, double h, std::size_t steps,
                       const RelativeCfm& soft) {
  const double grip_h = slide_grip(setup.mu, setup.g, model, setup.angle) * h;
  NormalSide out{{0.0}, {0.0}, soft.cfm / (1.0 + soft.cfm)};
  NormalState n;
  double sink_1 = 0.0;
  for (std::size_t k = 1; k <= steps; ++k) {
    const double impulse = normal_step(soft, setup.g, h, n);
    if (k == 1) sink_1 = n.d;
    out.grip_h.push_back(grip_h * (impulse / (setup.g * h)));
    out.off.push_back(n.d - sink_1);
  }
  return out;
}

}  // namespace

SlidePath slide_path(const SlideSetup& setup, FrictionModel model, double h, std::int64_t steps,
                     PositionUpdate position, const RelativeCfm& soft,
                     bool friction_after_position) {
  const NormalSide normal = normal_side(
      setup, model, h, static_cast<std::size_t>(std::max<std::int64_t>(steps, 0)), soft);
  SlidePath p;
  double s = 0.0, v = setup.v0;
  for (std::size_t n = 0; n < normal.grip_h.size(); ++n) {
    if (n > 0)
      slide_step(setup, normal.grip_h[n], normal.stick, h, position, friction_after_position, s, v);
    p.s.push_back(s);
    p.v.push_back(v);
    p.off.push_back(normal.off[n]);
  }
  return p;
}

SlidePath slide_steps(const SlideSetup& setup, FrictionModel model, double h, const SlidePath& from,
                      PositionUpdate position, const RelativeCfm& soft) {
  const NormalSide normal =
      normal_side(setup, model, h, from.s.empty() ? 0 : from.s.size() - 1, soft);
  SlidePath p;
  for (std::size_t n = 0; n < from.s.size(); ++n) {
    double s = n == 0 ? 0.0 : from.s[n - 1], v = n == 0 ? setup.v0 : from.v[n - 1];
    if (n > 0) slide_step(setup, normal.grip_h[n], normal.stick, h, position, false, s, v);
    p.s.push_back(s);
    p.v.push_back(v);
    p.off.push_back(normal.off[n]);
  }
  return p;
}

SlidePath slide_path_of(std::span<const BodyState> states, const SlideSetup& setup) {
  SlidePath p;
  if (states.empty()) return p;
  const Vec3 start = states[0].position;
  for (std::size_t k = 0; k < states.size(); ++k) {
    const BodyState& b = states[k];
    const Vec3 moved(b.position.x() - start.x(), 0.0, b.position.z() - start.z());
    const Vec3 v(b.velocity.x(), 0.0, b.velocity.z());
    const double along = moved.dot(setup.direction);
    p.s.push_back(along);
    p.v.push_back(std::copysign(v.norm(), v.dot(setup.direction)));  // across counts too
    // Across the slip, and up or down from where its contact put it after step 1 (an engine's
    // skin or sink sets that height): a slide that sinks, hops or tips on is off its law too.
    const double settled = states[std::min<std::size_t>(k, 1)].position.y();
    p.off.push_back(std::hypot((moved - along * setup.direction).norm(), b.position.y() - settled));
  }
  return p;
}

SlidePath observed_slide_path(const Trajectory& run, const SlideSetup& setup) {
  return slide_path_of(run.body_states(setup.body), setup);
}

SlideObservation observe_slide(const SlidePath& path, double stopped_speed, double settled) {
  SlideObservation o;
  if (path.s.empty()) return o;
  std::size_t n = path.s.size();  // the first index from which the body stays stopped
  while (n > 0 && std::abs(path.v[n - 1]) <= stopped_speed &&
         std::abs(path.s[n - 1] - path.s.back()) <= settled)
    --n;
  if (n == path.s.size()) {
    o.distance = path.s.back();
    return o;
  }
  o.stop_step = static_cast<std::int64_t>(n);
  o.distance = path.s[n];
  return o;
}

namespace {

// The contact test of a bounce law, its reach (contact distance) already scaled.
bool in_contact(const BounceLaw& law, double gap, double reach) {
  return gap < reach || gap < 0.0 || (law.touching && gap == 0.0);
}

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
    if (in_contact(law_, gap_, reach_)) {
      const double approach = law_.free_approach ? -v_free : -v_;
      const double rebound = e_ * approach;
      const bool restitutes = (law_.threshold_on_rebound ? rebound : approach) > law_.threshold;
      const double rest = restitutes ? std::min(rebound, law_.max_rebound) : 0.0;
      double target = rest - gap_ / h_;  // speculative: the gap may close this step
      if (gap_ < 0.0) {
        const double push = std::min(law_.erp * -gap_ / h_, law_.max_push);
        target = law_.push_in_position ? rest : std::max(push, rest);
        if (law_.push_in_position) moved = h_ * push;
      }
      v_ = std::max(v_free, (law_.cfm * v_free + target) / (1.0 + law_.cfm));
    } else {
      v_ = v_free;
    }
    gap_ += h_ * (law_.resolved_after_position ? v_free : v_) + moved;
  }
  double gap() const { return gap_; }
  double v() const { return v_; }
  // Restarts from a state (a run's, for its law one step ahead).
  void reset(double gap, double v) {
    gap_ = gap;
    v_ = v;
  }

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
    const bool pushed = n > 0 && v > v_ - gh_ + 1e-3 * gh_;
    if (pushed && o_.contact_step < 0) {
      // The floor pushed in step n: the impact is the step before (it ended in, or speculatively
      // near, the floor).
      o_.contact_step = n - 1;
      o_.speed_in = -v_;
      o_.speed_out = v;
      impact_ = true;
    } else if (pushed && impact_) {
      o_.speed_out = v;  // a soft contact pushes over several steps
    } else {
      impact_ = false;
      if (o_.contact_step >= 0 && v_ > 0.0 && v <= 0.0) o_.apexes.push_back(gap_);
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
  bool impact_ = false;  // every step since the first impact's has pushed
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

bool bounce_contact(const BounceLaw& law, double gap, double size) {
  return in_contact(law, gap, law.contact_distance + law.contact_distance_per_size * size);
}

BouncePath bounce_steps(const BounceLaw& law, const BouncePath& from, double e, double g, double h,
                        double size) {
  BouncePath p;
  if (from.gap.empty()) return p;
  BounceStepper sphere(law, from.gap[0], e, g, h, size);
  p.gap.push_back(from.gap[0]);
  p.v.push_back(from.v[0]);
  for (std::size_t n = 1; n < from.gap.size(); ++n) {
    sphere.reset(from.gap[n - 1], from.v[n - 1]);
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
  if (!floor_contact(scene) || !level_gravity(scene) || !m.restitution ||
      scene.world.damping_rate != 0.0)
    return out;
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

BouncePath bounce_path_of(std::span<const BodyState> states, const BounceSetup& setup) {
  BouncePath p;
  for (const BodyState& b : states) {
    p.gap.push_back(b.position.y() - setup.radius - setup.floor_top);
    p.v.push_back(b.velocity.y());
  }
  return p;
}

BouncePath observed_path(const Trajectory& run, const BounceSetup& setup) {
  return bounce_path_of(run.body_states(setup.body), setup);
}

}  // namespace dropcheck
