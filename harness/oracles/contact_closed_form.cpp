#include "harness/oracles/contact_closed_form.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "harness/oracles/analytic.hpp"
#include "harness/oracles/contact_laws.hpp"
#include "harness/oracles/landing.hpp"
#include "harness/oracles/stack.hpp"

namespace dropcheck {
namespace {

// One body's continuous state at time t.
using BodyPath = std::function<BodyState(double)>;

// At rest at `at` from the start.
BodyPath resting(const Vec3& at) {
  return [at](double) { return BodyState{at, Vec3::Zero()}; };
}

// Its free flight (the scene without contacts) until `landing` s, then at rest `rest_height` high
// where the flight put it.
BodyPath falls_then_rests(const Scene& free, std::size_t body, double landing, double rest_height) {
  return [&free, body, landing, rest_height](double t) {
    if (!(t >= landing)) return analytic_state(free, body, t);
    Vec3 at = analytic_state(free, body, landing).position;
    at.y() = rest_height;
    return BodyState{at, Vec3::Zero()};
  };
}

// The speed along the slip of slide_distance_continuous's motion (its derivative).
double slide_speed(double v0, double pull, double grip, double t) {
  if (v0 > 0.0) {
    const double a = grip - pull;
    if (a <= 0.0 || t <= v0 / a) return v0 - a * t;
    t -= v0 / a;
  }
  if (std::abs(pull) <= grip) return 0.0;
  return std::copysign((std::abs(pull) - grip) * t, pull);
}

BodyPath slides(const Body& b, const SlideSetup& s) {
  return [start = b.position, s](double t) {
    const double grip = s.mu * s.g;  // the Coulomb cone's
    return BodyState{start + s.direction * slide_distance_continuous(s.v0, s.pull, grip, t),
                     s.direction * slide_speed(s.v0, s.pull, grip, t)};
  };
}

// A sphere dropped from rest h0 above the floor: the fall, then flights of 2*e^n*t_fall leaving at
// e^n times the impact speed, then at rest once their sum is spent.
BodyPath bounces(const Body& b, const BounceSetup& s) {
  return [start = b.position, s](double t) {
    const double fall = std::sqrt(2.0 * s.h0 / s.g), v_in = s.g * fall;
    const double ground = s.floor_top + s.radius;
    Vec3 at = start;
    if (t <= fall) {
      at.y() = start.y() - 0.5 * s.g * t * t;
      return BodyState{at, Vec3(0.0, -s.g * t, 0.0)};
    }
    t -= fall;
    // Flight n (n = 0, 1, ...) lasts F0*e^n, F0 = 2*e*v_in/g: the first n flights take
    // F0*(1 - e^n)/(1 - e) (n*F0 when e = 1), all of them F0/(1 - e).
    const double f0 = 2.0 * s.e * v_in / s.g;
    double speed = s.e * v_in;
    if (!(f0 > 0.0) || (s.e < 1.0 && t >= f0 / (1.0 - s.e))) {
      at.y() = ground;
      return BodyState{at, Vec3::Zero()};
    }
    if (s.e >= 1.0) {
      t = std::fmod(t, f0);
    } else {
      const double n = std::floor(std::log1p(-t * (1.0 - s.e) / f0) / std::log(s.e));
      t = std::max(0.0, t - f0 * (1.0 - std::pow(s.e, n)) / (1.0 - s.e));
      speed *= std::pow(s.e, n);
    }
    at.y() = ground + speed * t - 0.5 * s.g * t * t;
    return BodyState{at, Vec3(0.0, speed - s.g * t, 0.0)};
  };
}

template <typename Setup>
const Setup* role_of(const std::vector<Setup>& setups, std::size_t body) {
  for (const Setup& s : setups)
    if (s.body == body) return &s;
  return nullptr;
}

const StackLevel* level_of(const std::vector<StackSetup>& stacks, std::size_t body) {
  for (const StackSetup& s : stacks)
    for (const StackLevel& l : s.levels)
      if (l.body == body) return &l;
  return nullptr;
}

// Whether body i starts at rest on what holds it: a stack level without a gap, or a landing whose
// bottom is on its floor.
bool at_rest(const std::vector<LandingSetup>& landing, const std::vector<StackSetup>& stacks,
             std::size_t i) {
  if (const StackLevel* l = level_of(stacks, i)) return l->gap == 0.0;
  const LandingSetup* l = role_of(landing, i);
  return l && l->contact_time == 0.0;
}

// Every dynamic body's path, or why one has none.
struct Paths {
  std::vector<BodyPath> of;  // indexed like Scene::bodies
  std::string why_none;
};

Paths paths(const Scene& scene, const Scene& free) {
  Paths p;
  if (!scene.world.contacts) {
    p.why_none = "no contacts";
    return p;
  }
  if (needs_rotation(scene)) {
    p.why_none = "a body turns";
    return p;
  }
  if (const std::string why = analytic_unavailable(free); !why.empty()) {
    p.why_none = why;
    return p;
  }
  const std::vector<StackSetup> stacks = stack_setups(scene);
  const std::vector<SlideSetup> slide = slide_setups(scene);
  const std::vector<BounceSetup> bounce = bounce_setups(scene);
  const std::vector<LandingSetup> landing = landing_setups(scene);
  const std::vector<LandingExclusion> excluded = landing_exclusions(scene);
  const double k = scene.world.damping_rate, a = scene.world.gravity.y();
  // With restitution only a bounce setup's sphere, a slide (launched along its floor, it never
  // leaves it), or a body that never leaves its rest, has the answer below: every other landing
  // would rebound.
  const bool restitutes = scene_material(scene).restitution.value_or(0.0) > 0.0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Body& b = scene.bodies[i];
    if (b.is_static) {
      p.of.push_back(resting(b.position));
    } else if (const BounceSetup* s = role_of(bounce, i)) {
      p.of.push_back(bounces(b, *s));
    } else if (const SlideSetup* s = role_of(slide, i)) {
      p.of.push_back(slides(b, *s));
    } else if (restitutes && !(b.velocity == Vec3::Zero() && at_rest(landing, stacks, i))) {
      p.why_none = "'" + b.name + "' lands with restitution outside a bounce setup";
      return p;
    } else if (const StackLevel* l = level_of(stacks, i)) {
      const double lands =
          l->gap > 0.0 ? contact_time_continuous(b.position.y(), 0.0, a, k, l->rest_height) : 0.0;
      p.of.push_back(falls_then_rests(free, i, lands, l->rest_height));
    } else if (const LandingSetup* l = role_of(landing, i);
               l && role_of(excluded, i) == nullptr && b.velocity.x() == 0.0 &&
               b.velocity.z() == 0.0 && !pushed(scene, i) && level_gravity(scene)) {
      p.of.push_back(falls_then_rests(free, i, l->contact_time, l->rest_height));
    } else {
      p.why_none = "'" + b.name + "' is no resting stack, slide, bounce or straight landing";
      return p;
    }
  }
  return p;
}

}  // namespace

std::string contact_closed_form_unavailable(const Scene& scene) {
  Scene free = scene;
  free.world.contacts = false;
  return paths(scene, free).why_none;
}

std::optional<Trajectory> contact_closed_form(const Scene& scene, double h) {
  Scene free = scene;
  free.world.contacts = false;
  const Paths p = paths(scene, free);
  if (!p.why_none.empty()) return std::nullopt;
  return sampled_answer(scene, h, 1, "closed form",
                        [&p](std::size_t i, double t) { return p.of[i](t); });
}

std::optional<Trajectory> closed_form_trajectory(const Scene& scene, double h) {
  return scene.world.contacts ? contact_closed_form(scene, h) : analytic_trajectory(scene, h);
}

std::string closed_form_unavailable(const Scene& scene) {
  return scene.world.contacts ? contact_closed_form_unavailable(scene)
                              : analytic_unavailable(scene);
}

}  // namespace dropcheck
