// The quantities a scene's [expect] table may state (docs/design.md, "Scenario files"), each by
// name with what the harness computes of it from the scene: the closed forms and ideal discrete
// laws of harness/oracles/*, the stability theory, and plain geometry. A new kind of figure adds
// its name and computation here.
//
// A quantity is the scene's (damping_rate) or one body's (contact_time). Names: the continuous
// model's figure plainly (stop_distance); the ideal discrete law's at the scene's step with law_
// (law_stop_distance); a friction pyramid's with its model (_box_pyramid, _sum_pyramid; none: the
// cone).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "harness/oracles/analytic.hpp"
#include "harness/oracles/contact_laws.hpp"
#include "harness/oracles/free_rotation.hpp"
#include "harness/oracles/landing.hpp"
#include "harness/oracles/stability_theory.hpp"
#include "harness/oracles/stack.hpp"

namespace dropcheck::testing {

// What a quantity gives: nullopt where it does not apply (a scene without slides, a static body).
using SceneQuantity = std::function<std::optional<double>(const Scene&)>;
using BodyQuantity = std::function<std::optional<double>(const Scene&, std::size_t body)>;
struct Quantity {
  SceneQuantity of_scene;  // the scene's, or
  BodyQuantity of_body;    // one body's
};

namespace quantity {

constexpr double kDegree = M_PI / 180.0;

// Sum of the constant forces on body i (N).
inline Vec3 constant_force(const Scene& s, std::size_t i) {
  Vec3 f = Vec3::Zero();
  for (const Force& force : s.forces)
    if (const auto* c = std::get_if<ConstantForce>(&force.law))
      if (std::find(force.bodies.begin(), force.bodies.end(), i) != force.bodies.end())
        f += c->force;
  return f;
}

// Springs on body i (rest length 0): stiffness sum S, dashpot sum C, anchor S-weighted mean A; the
// body sees F = -S*(x - A) - C*v.
struct Springs {
  double S = 0.0, C = 0.0;
  Vec3 A = Vec3::Zero();
};
inline Springs springs(const Scene& s, std::size_t i) {
  Springs out;
  for (const Force& force : s.forces)
    if (const auto* sp = std::get_if<Spring>(&force.law))
      if (std::find(force.bodies.begin(), force.bodies.end(), i) != force.bodies.end()) {
        out.S += sp->stiffness;
        out.C += sp->damping;
        out.A += sp->stiffness * sp->anchor;
      }
  if (out.S > 0.0) out.A /= out.S;
  return out;
}

// Acceleration of body i from gravity and constant forces (springs aside).
inline Vec3 acceleration(const Scene& s, std::size_t i) {
  return s.world.gravity + constant_force(s, i) / s.bodies[i].mass;
}

// Angular frequency of body i on its springs: omega = sqrt(S/m).
inline double omega(const Scene& s, std::size_t i) {
  return std::sqrt(springs(s, i).S / s.bodies[i].mass);
}

// Time at which vertical velocity v0 > 0 under vertical acceleration a < 0 and drag k reaches 0:
// v(t) = a/k + (v0 - a/k)*exp(-k*t) = 0  ->  t = ln(1 + k*v0/|a|)/k  (k = 0: v0/|a|).
inline double apex_time(double v0, double a, double k) {
  return k == 0.0 ? v0 / -a : std::log1p(k * v0 / -a) / k;
}

// Spacing of float numbers just above |c|: what a float engine can resolve at coordinate c.
inline double float_spacing(double c) {
  const float f = static_cast<float>(std::abs(c));
  return static_cast<double>(std::nextafter(f, INFINITY)) - static_cast<double>(f);
}

// The steps of the scene's sweep.
inline std::vector<double> sweep_steps(const Scene& s) {
  std::vector<double> h;
  for (const Timestep& t : s.timesteps) h.push_back(t.seconds);
  return h;
}

// Gravity's angle from straight down (deg): the incline a tilted gravity models.
inline double incline(const Scene& s) {
  const Vec3& g = s.world.gravity;
  return std::atan2(std::hypot(g.x(), g.z()), -g.y()) / kDegree;
}

// The setup of body i among `all` (landings, slides, bounces), if it has one.
template <class Setup>
std::optional<Setup> setup_of(const std::vector<Setup>& all, std::size_t i) {
  for (const Setup& x : all)
    if (x.body == i) return x;
  return std::nullopt;
}

// `f` of body i, where `applies` holds for it.
inline BodyQuantity where(std::function<bool(const Scene&, std::size_t)> applies,
                          std::function<double(const Scene&, std::size_t)> f) {
  return [applies, f](const Scene& s, std::size_t i) -> std::optional<double> {
    if (!applies(s, i)) return std::nullopt;
    return f(s, i);
  };
}
inline bool is_dynamic(const Scene& s, std::size_t i) {
  return !s.bodies[i].is_static;
}
inline bool is_floor(const Scene& s, std::size_t i) {
  return s.bodies[i].is_static;
}
inline bool is_sprung(const Scene& s, std::size_t i) {
  return is_dynamic(s, i) && springs(s, i).S > 0.0;
}
inline bool is_free(const Scene& s, std::size_t i) {
  return is_dynamic(s, i) && springs(s, i).S == 0.0;
}
// Thrown upwards, free of springs: it has an apex.
inline bool is_thrown_up(const Scene& s, std::size_t i) {
  return is_free(s, i) && s.bodies[i].velocity.y() > 0.0 && acceleration(s, i).y() < 0.0;
}
// The continuous model of harness/oracles/analytic.hpp covers the scene.
inline bool has_closed_form(const Scene& s, std::size_t i) {
  return is_dynamic(s, i) && analytic_unavailable(s).empty();
}
inline bool is_turning(const Scene& s, std::size_t i) {
  return is_dynamic(s, i) && s.bodies[i].angular_velocity.norm() > 0.0;
}

// `f` of body i's setup among `setups(scene)`, where it has one.
template <class Setup>
BodyQuantity of_setup(std::function<std::vector<Setup>(const Scene&)> setups,
                      std::function<double(const Scene&, const Setup&)> f) {
  return [setups, f](const Scene& s, std::size_t i) -> std::optional<double> {
    const std::optional<Setup> x = setup_of(setups(s), i);
    if (!x) return std::nullopt;
    return f(s, *x);
  };
}

// A landing's continuous figures (harness/oracles/landing.hpp).
inline BodyQuantity landing(std::function<double(const Scene&, const LandingSetup&)> f) {
  return of_setup<LandingSetup>(landing_setups, std::move(f));
}

// A bouncing sphere's closed form and ideal discrete law at the scene's step.
inline BodyQuantity bouncing(std::function<double(const Bounce&)> f) {
  return of_setup<BounceSetup>(bounce_setups, [f](const Scene& s, const BounceSetup& b) {
    return f(bounce(b.h0, b.e, b.g, s.timestep.seconds));
  });
}

// A slide's setup (harness/oracles/contact_laws.hpp).
inline BodyQuantity sliding(std::function<double(const Scene&, const SlideSetup&)> f) {
  return of_setup<SlideSetup>(slide_setups, std::move(f));
}

// A slide to a stop under friction `model`, continuous and ideal discrete law at the scene's step.
inline BodyQuantity stopping(FrictionModel model, std::function<double(const SlideStop&)> f) {
  return sliding([model, f](const Scene& s, const SlideSetup& l) {
    return f(slide_to_stop(l.v0, l.mu, l.g, s.timestep.seconds, model, l.angle, l.pull));
  });
}

// A stacked body's level (harness/oracles/stack.hpp).
inline std::vector<StackLevel> stack_levels(const Scene& s) {
  std::vector<StackLevel> out;
  for (const StackSetup& stack : stack_setups(s))
    out.insert(out.end(), stack.levels.begin(), stack.levels.end());
  return out;
}

// The edge of a spring scene's step under `order` (harness/oracles/stability_theory.cpp).
inline std::optional<double> edge(const Scene& s, DampingOrder order) {
  return theory_max_dt(s, order);
}

// The edge every damping order shares (an undamped spring), or nullopt where they differ.
inline std::optional<double> common_edge(const Scene& s) {
  const std::optional<double> first = edge(s, DampingOrder::AfterForces);
  for (DampingOrder o : {DampingOrder::BeforeForces, DampingOrder::AfterPosition}) {
    const std::optional<double> e = edge(s, o);
    if (!first || !e || std::abs(*e - *first) > 1e-12 * *first) return std::nullopt;
  }
  return first;
}

// A body on springs of rest length 0: a linear oscillator of omega = sqrt(S/m).
inline void add_spring_quantities(std::map<std::string, Quantity>& q) {
  const auto body = [&q](const std::string& name,
                         std::function<double(const Scene&, std::size_t)> f) {
    q[name] = {{}, where(is_sprung, std::move(f))};
  };
  body("omega", omega);
  body("omega_h", [](const Scene& s, std::size_t i) { return omega(s, i) * s.timestep.seconds; });
  body("omega_h_min", [](const Scene& s, std::size_t i) {
    const std::vector<double> h = sweep_steps(s);
    return omega(s, i) * *std::min_element(h.begin(), h.end());
  });
  body("omega_h_max", [](const Scene& s, std::size_t i) {
    const std::vector<double> h = sweep_steps(s);
    return omega(s, i) * *std::max_element(h.begin(), h.end());
  });
  body("anchor_above_start", [](const Scene& s, std::size_t i) {
    return springs(s, i).A.y() - s.bodies[i].position.y();
  });
  // Equilibrium x_eq = A + (m*g + F)/S: its distance from the start.
  body("sag", [](const Scene& s, std::size_t i) {
    const Springs sp = springs(s, i);
    const Vec3 eq = sp.A + s.bodies[i].mass * acceleration(s, i) / sp.S;
    return (eq - s.bodies[i].position).norm();
  });
  body("oscillations",
       [](const Scene& s, std::size_t i) { return s.duration * omega(s, i) / (2.0 * M_PI); });
  // Semi-implicit Euler on an undamped oscillator turns by theta per step, with
  // 2*sin(theta/2) = w*h: its frequency is high by theta/(w*h) - 1 = (w*h)^2/24 + O(h^4).
  body("frequency_error", [](const Scene& s, std::size_t i) {
    const double wh = omega(s, i) * s.timestep.seconds;
    return 2.0 * std::asin(wh / 2.0) / wh - 1.0;
  });
}

// The scene's own quantities.
inline void add_scene_quantities(std::map<std::string, Quantity>& q) {
  const auto scene = [&q](const std::string& name, SceneQuantity f) { q[name] = {f, {}}; };
  scene("gravity", [](const Scene& s) { return s.world.gravity.norm(); });
  scene("damping_rate", [](const Scene& s) { return s.world.damping_rate; });
  scene("incline", [](const Scene& s) { return incline(s); });
  scene("tan_incline", [](const Scene& s) { return std::tan(incline(s) * kDegree); });
  scene("steps",
        [](const Scene& s) { return static_cast<double>(step_count(s, s.timestep.seconds)); });
  // k*h, the damping of one step, over the sweep.
  scene("kh_min", [](const Scene& s) {
    const std::vector<double> h = sweep_steps(s);
    return s.world.damping_rate * *std::min_element(h.begin(), h.end());
  });
  scene("kh_max", [](const Scene& s) {
    const std::vector<double> h = sweep_steps(s);
    return s.world.damping_rate * *std::max_element(h.begin(), h.end());
  });
  // The largest stable step of semi-implicit Euler on the scene's springs, per damping order.
  scene("stability_edge", common_edge);
  scene("stability_edge_after_forces",
        [](const Scene& s) { return edge(s, DampingOrder::AfterForces); });
  scene("stability_edge_before_forces",
        [](const Scene& s) { return edge(s, DampingOrder::BeforeForces); });
  scene("stability_edge_after_position",
        [](const Scene& s) { return edge(s, DampingOrder::AfterPosition); });
}

// A body's geometry, motion and springs.
inline void add_body_quantities(std::map<std::string, Quantity>& q) {
  const auto body = [&q](const std::string& name, BodyQuantity f) { q[name] = {{}, f}; };
  body("mass", where(is_dynamic, [](const Scene& s, std::size_t i) { return s.bodies[i].mass; }));
  body("mass_ratio", where(is_dynamic, [](const Scene& s, std::size_t i) {  // to the lightest
         double lightest = INFINITY;
         for (std::size_t j = 0; j < s.bodies.size(); ++j)
           if (is_dynamic(s, j)) lightest = std::min(lightest, s.bodies[j].mass);
         return s.bodies[i].mass / lightest;
       }));
  for (int k = 0; k < 3; ++k) {
    const std::string axis(1, "xyz"[k]);
    body("side_" + axis, where(is_dynamic, [k](const Scene& s, std::size_t i) {
           return 2.0 * s.bodies[i].half_extents[k];
         }));
    body("float_spacing_" + axis, where(is_dynamic, [k](const Scene& s, std::size_t i) {
           return float_spacing(s.bodies[i].position[k]);
         }));
  }
  body("floor_top", where(is_floor, [](const Scene& s, std::size_t i) {
         return s.bodies[i].position.y() + s.bodies[i].half_extents.y();
       }));
  body("floor_thickness", where(is_floor, [](const Scene& s, std::size_t i) {
         return 2.0 * s.bodies[i].half_extents.y();
       }));
  body("step_travel", where(is_dynamic, [](const Scene& s, std::size_t i) {
         return s.bodies[i].velocity.norm() * s.timestep.seconds;
       }));
  // Free flight, continuous model (harness/oracles/analytic.hpp): over the whole run.
  body("fall", where(has_closed_form, [](const Scene& s, std::size_t i) {
         return s.bodies[i].position.y() - analytic_state(s, i, s.duration).position.y();
       }));
  body("end_speed", where(has_closed_form, [](const Scene& s, std::size_t i) {
         return analytic_state(s, i, s.duration).velocity.norm();
       }));
  // dv/dt = a - k*v settles at |a|/k.
  body("terminal_speed", where(is_free, [](const Scene& s, std::size_t i) {
         return acceleration(s, i).norm() / s.world.damping_rate;
       }));
  body("net_acceleration",
       where(is_dynamic, [](const Scene& s, std::size_t i) { return acceleration(s, i).norm(); }));
  body("apex_time", where(is_thrown_up, [](const Scene& s, std::size_t i) {
         return apex_time(s.bodies[i].velocity.y(), acceleration(s, i).y(), s.world.damping_rate);
       }));
  body("rise", where(is_thrown_up, [](const Scene& s, std::size_t i) {
         const double v0 = s.bodies[i].velocity.y(), a = acceleration(s, i).y();
         const double k = s.world.damping_rate;
         return height_continuous(0.0, v0, a, k, apex_time(v0, a, k));
       }));
  // Rotation: dw/dt = -k_a*w decays the spin to w*exp(-k_a*T) and turns the body through
  // w*(1 - exp(-k_a*T))/k_a (w*T undamped); torque-free, a box flips each half period of w(t).
  body("spin_at_end", where(is_dynamic, [](const Scene& s, std::size_t i) {
         return s.bodies[i].angular_velocity.norm() *
                std::exp(-s.world.angular_damping_rate * s.duration);
       }));
  body("turn", where(is_dynamic, [](const Scene& s, std::size_t i) {
         const double k = s.world.angular_damping_rate, t = s.duration;
         const double w = s.bodies[i].angular_velocity.norm();
         return k == 0.0 ? w * t : w * -std::expm1(-k * t) / k;
       }));
  body("flip_period", where(is_turning, [](const Scene& s, std::size_t i) {
         const Body& b = s.bodies[i];
         const Vec3 w_body = b.orientation.conjugate() * b.angular_velocity;
         return FreeRotation(inertia_of(b), w_body).period() / 2.0;
       }));
  add_spring_quantities(q);
}

// A slide: its geometry, its continuous closed form and its ideal discrete law per friction model.
inline void add_slide_quantities(std::map<std::string, Quantity>& q) {
  const auto body = [&q](const std::string& name, BodyQuantity f) { q[name] = {{}, f}; };
  body("slide_angle", sliding([](const Scene&, const SlideSetup& l) { return l.angle / kDegree; }));
  body("friction_needed",
       sliding([](const Scene&, const SlideSetup& l) { return std::abs(l.pull); }));
  body("friction_available", sliding([](const Scene&, const SlideSetup& l) { return l.mu * l.g; }));
  body("slide_acceleration",
       sliding([](const Scene&, const SlideSetup& l) { return l.pull - l.mu * l.g; }));
  body("slide_distance", sliding([](const Scene& s, const SlideSetup& l) {
         return slide_distance_continuous(l.v0, l.pull, l.mu * l.g, s.duration);
       }));
  body("law_slide_distance", sliding([](const Scene& s, const SlideSetup& l) {
         const double h = s.timestep.seconds;
         return slide_path(l, FrictionModel::cone, h, step_count(s, h)).s.back();
       }));
  const std::pair<FrictionModel, std::string> models[] = {
      {FrictionModel::cone, ""},
      {FrictionModel::box_pyramid, "_box_pyramid"},
      {FrictionModel::sum_pyramid, "_sum_pyramid"}};
  for (const auto& [model, suffix] : models) {
    body("stop_time" + suffix, stopping(model, [](const SlideStop& l) { return l.stop_time; }));
    body("stop_distance" + suffix, stopping(model, [](const SlideStop& l) { return l.distance; }));
    body("law_stop_step" + suffix,
         stopping(model, [](const SlideStop& l) { return double(l.stop_step); }));
    body("law_stop_distance" + suffix,
         stopping(model, [](const SlideStop& l) { return l.step_distance; }));
  }
}

// Landings, bounces, slides and stacks (harness/oracles/landing.hpp, contact_laws.hpp, stack.hpp).
inline void add_contact_quantities(std::map<std::string, Quantity>& q) {
  const auto body = [&q](const std::string& name, BodyQuantity f) { q[name] = {{}, f}; };
  body("contact_time", landing([](const Scene&, const LandingSetup& l) { return l.contact_time; }));
  body("rest_height", landing([](const Scene&, const LandingSetup& l) { return l.rest_height; }));
  // |v(t_c)| of dv/dt = a - k*v: v(t) = a/k + (v0 - a/k)*exp(-k*t)  (k = 0: v0 + a*t).
  body("landing_speed", landing([](const Scene& s, const LandingSetup& l) {
         const double v0 = s.bodies[l.body].velocity.y(), a = acceleration(s, l.body).y();
         const double k = s.world.damping_rate, t = l.contact_time;
         return std::abs(k == 0.0 ? v0 + a * t : a / k + (v0 - a / k) * std::exp(-k * t));
       }));
  body("stack_rest_height",
       of_setup<StackLevel>(stack_levels,
                            [](const Scene&, const StackLevel& l) { return l.rest_height; }));
  body("drop_height", of_setup<BounceSetup>(
                          bounce_setups, [](const Scene&, const BounceSetup& b) { return b.h0; }));
  for (std::size_t n = 0; n < 3; ++n)
    body("apex_" + std::to_string(n + 1), bouncing([n](const Bounce& b) { return b.apexes[n]; }));
  body("rest_time", bouncing([](const Bounce& b) { return b.time_to_rest; }));
  body("law_contact_step", bouncing([](const Bounce& b) { return double(b.contact_step); }));
  body("law_speed_in", bouncing([](const Bounce& b) { return b.step_speed_in; }));
  body("law_speed_out", bouncing([](const Bounce& b) { return b.step_speed_out; }));
  body("law_apex", bouncing([](const Bounce& b) { return b.step_apex; }));
  add_slide_quantities(q);
}

}  // namespace quantity

// Every quantity an [expect] table may name.
inline const std::map<std::string, Quantity>& quantities() {
  static const std::map<std::string, Quantity> all = [] {
    std::map<std::string, Quantity> q;
    quantity::add_scene_quantities(q);
    quantity::add_body_quantities(q);
    quantity::add_contact_quantities(q);
    return q;
  }();
  return all;
}

}  // namespace dropcheck::testing
