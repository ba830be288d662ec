// Tests that scene descriptions do not contradict their scenes: every figure a description states
// sits in a phrase this file knows ("first contact at t = 1.919 s", "k = 1.2122 1/s", ...) and
// agrees with what the harness computes from the scene to the precision the description writes
// (half a unit in the last digit written); any other digit in a description is refused. A writer
// who wants a new kind of figure adds its phrase here with the computation that checks it.
// The convention is documented in docs/design.md ("Scenario files").
#include <algorithm>
#include <catch2/catch.hpp>

// GCC 12 at -O2 warns -Wmaybe-uninitialized inside <regex>'s own std::function members (a known
// false positive in a system header, the one tests/CMakeLists.txt silences for main.cpp); under
// -Werror (the ci preset) it would fail the build. Off for this file, which instantiates <regex>.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "harness/judge/stability_classify.hpp"
#include "harness/oracles/analytic.hpp"
#include "harness/oracles/contact_laws.hpp"
#include "harness/oracles/free_rotation.hpp"
#include "harness/oracles/landing.hpp"
#include "harness/oracles/stability_theory.hpp"
#include "harness/oracles/stack.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/shipped_scenes.hpp"

namespace {

using dropcheck::Body;
using dropcheck::Scene;
using dropcheck::Vec3;

// A number as descriptions write it: 0.98, 216000, 1e-5, 1.2e-7.
const std::string N = R"(([0-9]+(?:\.[0-9]+)?(?:e-?[0-9]+)?))";

// Half a unit in the last digit written: "1.919" -> 5e-4, "1e-5" -> 5e-6, "60" -> 0.5.
double half_unit(const std::string& text) {
  const std::size_t e = text.find('e');
  const std::string mantissa = text.substr(0, e);
  const int exponent = e == std::string::npos ? 0 : std::stoi(text.substr(e + 1));
  const std::size_t dot = mantissa.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(mantissa.size() - dot - 1);
  return 0.5 * std::pow(10.0, exponent - decimals);
}

// "" when `text` rounds any of `values` (within half a unit of its last digit, plus 1e-9 relative
// for values such as 1/(1/60) that are exact in decimal but not in binary); else what was expected.
std::string agrees(const std::string& text, const std::vector<double>& values) {
  const double stated = std::stod(text);
  const double tol = half_unit(text) * (1.0 + 1e-9) + 1e-9 * std::abs(stated);
  std::ostringstream expected;
  expected.precision(6);
  for (double v : values) {
    if (std::abs(v - stated) <= tol) return "";
    expected << (expected.tellp() > 0 ? " or " : "") << v;
  }
  return "states " + text + ", the scene gives " +
         (values.empty() ? std::string("no such quantity") : expected.str());
}

// Per-body quantities the phrases need.
Vec3 constant_force(const Scene& s, std::size_t i) {
  Vec3 f = Vec3::Zero();
  for (const dropcheck::Force& force : s.forces)
    if (const auto* c = std::get_if<dropcheck::ConstantForce>(&force.law))
      if (std::find(force.bodies.begin(), force.bodies.end(), i) != force.bodies.end())
        f += c->force;
  return f;
}

// Springs on body i (rest length 0): stiffness sum S, dashpot sum C, anchor S-weighted mean A.
struct Springs {
  double S = 0.0, C = 0.0;
  Vec3 A = Vec3::Zero();
};
Springs springs(const Scene& s, std::size_t i) {
  Springs out;
  for (const dropcheck::Force& force : s.forces)
    if (const auto* sp = std::get_if<dropcheck::Spring>(&force.law))
      if (std::find(force.bodies.begin(), force.bodies.end(), i) != force.bodies.end()) {
        out.S += sp->stiffness;
        out.C += sp->damping;
        out.A += sp->stiffness * sp->anchor;
      }
  if (out.S > 0.0) out.A /= out.S;
  return out;
}

// Acceleration of body i from gravity and constant forces (springs aside).
Vec3 acceleration(const Scene& s, std::size_t i) {
  return s.world.gravity + constant_force(s, i) / s.bodies[i].mass;
}

// Collects f(scene, body index) over dynamic bodies (with or without springs, as asked).
// A vector as descriptions write it: "(-2, 8, -2)"; each component a capture group.
const std::string V =
    R"(\((-?[0-9]+(?:\.[0-9]+)?), (-?[0-9]+(?:\.[0-9]+)?), (-?[0-9]+(?:\.[0-9]+)?)\))";

// The vector `f` gives for each dynamic body.
std::vector<Vec3> over_vectors(const Scene& s, const std::function<Vec3(const Body&)>& f) {
  std::vector<Vec3> out;
  for (const Body& b : s.bodies)
    if (!b.is_static) out.push_back(f(b));
  return out;
}

// "" when the three components m[1..3] round one of `vectors`, component by component.
std::string agrees_vector(const std::smatch& m, const std::vector<Vec3>& vectors) {
  std::string problem = "no body has that vector";
  for (const Vec3& v : vectors) {
    problem.clear();
    for (int k = 0; k < 3 && problem.empty(); ++k) problem = agrees(m[k + 1], {v[k]});
    if (problem.empty()) return problem;
  }
  return problem;
}

enum class Which { free, sprung, any };
std::vector<double> over_bodies(const Scene& s, Which which,
                                const std::function<double(std::size_t)>& f) {
  std::vector<double> out;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    if (s.bodies[i].is_static) continue;
    const bool sprung = springs(s, i).S > 0.0;
    if ((which == Which::free && sprung) || (which == Which::sprung && !sprung)) continue;
    out.push_back(f(i));
  }
  return out;
}

double omega(const Scene& s, std::size_t i) {
  return std::sqrt(springs(s, i).S / s.bodies[i].mass);
}

// Time at which vertical velocity v0 > 0 under vertical acceleration a < 0 and drag k reaches 0:
// v(t) = a/k + (v0 - a/k)*exp(-k*t) = 0  ->  t = ln(1 + k*v0/|a|)/k  (k = 0: v0/|a|).
double apex_time(double v0, double a, double k) {
  return k == 0.0 ? v0 / -a : std::log1p(k * v0 / -a) / k;
}

// Bodies thrown upwards, free of springs: the apex phrases apply to them.
std::vector<std::size_t> thrown_up(const Scene& s) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < s.bodies.size(); ++i)
    if (!s.bodies[i].is_static && springs(s, i).S == 0.0 && s.bodies[i].velocity.y() > 0.0 &&
        acceleration(s, i).y() < 0.0)
      out.push_back(i);
  return out;
}

// Spacing of float numbers just above |c|: what a float engine can resolve at coordinate c.
double float_spacing(double c) {
  const float f = static_cast<float>(std::abs(c));
  return static_cast<double>(std::nextafter(f, INFINITY)) - static_cast<double>(f);
}

std::vector<double> sweep_steps(const Scene& s) {
  std::vector<double> h;
  for (const dropcheck::Timestep& t : s.timesteps) h.push_back(t.seconds);
  return h;
}

// "## 5." headings of docs/engines.md, the sections descriptions may cite.
bool engines_md_has_section(const std::string& number) {
  std::ifstream in(DROPCHECK_SOURCE_DIR "/docs/engines.md");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("## " + number + ". ", 0) == 0) return true;
  return false;
}

// One phrase that may carry figures: its pattern (captures are the numbers) and its check, which
// returns "" when the figures agree with the scene.
struct Phrase {
  std::string pattern;
  std::function<std::string(const Scene&, const std::smatch&)> check;
};

// Values of f over the sweep's steps: its smallest and largest, for "from X to Y" phrases.
std::string range_over_sweep(const Scene& s, const std::smatch& m,
                             const std::function<std::vector<double>(double)>& f) {
  std::vector<double> all;
  for (double h : sweep_steps(s))
    for (double v : f(h)) all.push_back(v);
  if (all.empty()) return agrees(m[1], {});
  const std::string lo = agrees(m[1], {*std::min_element(all.begin(), all.end())});
  return lo.empty() ? agrees(m[2], {*std::max_element(all.begin(), all.end())}) : lo;
}

// One `field` per landing the scene's landing oracle judges (harness/oracles/landing.hpp).
std::vector<double> per_landing(const Scene& s, double dropcheck::LandingSetup::*field) {
  std::vector<double> out;
  for (const dropcheck::LandingSetup& l : dropcheck::landing_setups(s)) out.push_back(l.*field);
  return out;
}

// `field` of the slide law of `model` for each slide of the scene
// (harness/oracles/contact_laws.hpp), at the scene's step.
std::vector<double> per_slide(const Scene& s, dropcheck::FrictionModel model,
                              const std::function<double(const dropcheck::SlideStop&)>& field) {
  std::vector<double> out;
  for (const dropcheck::SlideSetup& l : dropcheck::slide_setups(s))
    out.push_back(field(
        dropcheck::slide_to_stop(l.v0, l.mu, l.g, s.timestep.seconds, model, l.angle, l.pull)));
  return out;
}

// `field` of the bounce (closed form and ideal discrete law) of each bouncing sphere of the scene,
// at the scene's step.
std::vector<double> per_bounce(const Scene& s,
                               const std::function<double(const dropcheck::Bounce&)>& field) {
  std::vector<double> out;
  for (const dropcheck::BounceSetup& b : dropcheck::bounce_setups(s))
    out.push_back(field(dropcheck::bounce(b.h0, b.e, b.g, s.timestep.seconds)));
  return out;
}

dropcheck::FrictionModel model_named(const std::string& name) {
  if (name == "box pyramid") return dropcheck::FrictionModel::box_pyramid;
  if (name == "sum pyramid") return dropcheck::FrictionModel::sum_pyramid;
  return dropcheck::FrictionModel::cone;
}

const std::vector<Phrase>& phrases() {
  using dropcheck::landing_setups;
  static const std::vector<Phrase> list = {
      // Phrases that contain shorter ones ("h = X s", "at x = X m") come first.
      // A slide to a stop (harness/oracles/contact_laws.hpp, docs/contact.md).
      {"(cone|box pyramid|sum pyramid)[^()]*\\(step " + N + ", " + N + " m\\)",
       [](const Scene& s, const std::smatch& m) {
         const dropcheck::FrictionModel model = model_named(m[1]);
         const std::string step = agrees(
             m[2], per_slide(s, model, [](const auto& l) { return double(l.stop_step); }));
         return step.empty() ? agrees(m[3], per_slide(s, model, [](const auto& l) {
                                 return l.step_distance;
                               }))
                             : step;
       }},
      {"continuous distances are " + N + ", " + N + " and " + N + " m",
       [](const Scene& s, const std::smatch& m) {
         int k = 1;
         for (auto model : {dropcheck::FrictionModel::cone, dropcheck::FrictionModel::box_pyramid,
                            dropcheck::FrictionModel::sum_pyramid}) {
           const std::string p =
               agrees(m[k++], per_slide(s, model, [](const auto& l) { return l.distance; }));
           if (!p.empty()) return p;
         }
         return std::string();
       }},
      {"stops it after " + N + " s and " + N + " m",
       [](const Scene& s, const std::smatch& m) {
         const auto cone = dropcheck::FrictionModel::cone;
         const std::string t =
             agrees(m[1], per_slide(s, cone, [](const auto& l) { return l.stop_time; }));
         return t.empty() ? agrees(m[2], per_slide(s, cone, [](const auto& l) { return l.distance; }))
                          : t;
       }},
      {"at step " + N + " after " + N + " m",
       [](const Scene& s, const std::smatch& m) {
         const auto cone = dropcheck::FrictionModel::cone;
         const std::string n = agrees(
             m[1], per_slide(s, cone, [](const auto& l) { return double(l.stop_step); }));
         return n.empty()
                    ? agrees(m[2], per_slide(s, cone, [](const auto& l) { return l.step_distance; }))
                    : n;
       }},
      // A dropped sphere's bounces (harness/oracles/contact_laws.hpp, docs/contact.md).
      {"continuous apexes are " + N + ", " + N + " and " + N + " m",
       [](const Scene& s, const std::smatch& m) {
         for (int k = 0; k < 3; ++k) {
           const std::string p = agrees(m[k + 1], per_bounce(s, [k](const auto& b) {
                                          return b.apexes[static_cast<std::size_t>(k)];
                                        }));
           if (!p.empty()) return p;
         }
         return std::string();
       }},
      {"comes to rest after " + N + " s",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], per_bounce(s, [](const auto& b) { return b.time_to_rest; }));
       }},
      {"hits at step " + N + " at " + N + " m/s, leaves at " + N + " m/s and climbs to (-?)" + N +
           " m",
       [](const Scene& s, const std::smatch& m) {
         const std::string step =
             agrees(m[1], per_bounce(s, [](const auto& b) { return double(b.contact_step); }));
         if (!step.empty()) return step;
         const std::string in =
             agrees(m[2], per_bounce(s, [](const auto& b) { return b.step_speed_in; }));
         if (!in.empty()) return in;
         const std::string out =
             agrees(m[3], per_bounce(s, [](const auto& b) { return b.step_speed_out; }));
         if (!out.empty()) return out;
         const double sign = m[4].length() > 0 ? -1.0 : 1.0;
         return agrees(m[5], per_bounce(s, [sign](const auto& b) { return sign * b.step_apex; }));
       }},
      {"lowest point " + N + " m above the floor",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> v;
         for (const auto& b : dropcheck::bounce_setups(s)) v.push_back(b.h0);
         return agrees(m[1], v);
       }},
      {"sphere of radius " + N + " m",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> v;
         for (const auto& b : dropcheck::bounce_setups(s)) v.push_back(b.radius);
         return agrees(m[1], v);
       }},
      {"restitution e = " + N,
       [](const Scene& s, const std::smatch& m) {
         const auto e = dropcheck::scene_material(s).restitution;
         return agrees(m[1], e ? std::vector<double>{*e} : std::vector<double>{});
       }},
      // A resting stack (harness/oracles/stack.hpp).
      {"rest heights, " + N + " and " + N + " m",
       [](const Scene& s, const std::smatch& m) {
         // In order: the bottom level's, then the next (of the first stack).
         const auto stacks = dropcheck::stack_setups(s);
         if (stacks.empty() || stacks[0].levels.size() < 2) return agrees(m[1], {});
         const std::string p = agrees(m[1], {stacks[0].levels[0].rest_height});
         return p.empty() ? agrees(m[2], {stacks[0].levels[1].rest_height}) : p;
       }},
      // A slide on an incline: gravity tilted by theta (harness/oracles/contact_laws.hpp).
      {"(?:incline of|tilted by) " + N + " degrees",
       [](const Scene& s, const std::smatch& m) {
         const Vec3& g = s.world.gravity;
         return agrees(m[1], {std::atan2(std::hypot(g.x(), g.z()), -g.y()) * 180.0 / M_PI});
       }},
      {"tan\\(" + N + " degrees\\) = " + N,
       [](const Scene&, const std::smatch& m) {
         return agrees(m[2], {std::tan(std::stod(m[1]) * M_PI / 180.0)});
       }},
      {"needs " + N + " m/s\\^2 of friction where " + N + " m/s\\^2 is available",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> pull, grip;
         for (const auto& l : dropcheck::slide_setups(s)) {
           pull.push_back(std::abs(l.pull));
           grip.push_back(l.mu * l.g);
         }
         const std::string p = agrees(m[1], pull);
         return p.empty() ? agrees(m[2], grip) : p;
       }},
      {"accelerates at g\\*\\(sin - mu\\*cos\\) = " + N + " m/s\\^2",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> a;
         for (const auto& l : dropcheck::slide_setups(s)) a.push_back(l.pull - l.mu * l.g);
         return agrees(m[1], a);
       }},
      {"slides " + N + " m in " + N + " s\\b",
       [](const Scene& s, const std::smatch& m) {
         const double t = std::stod(m[2]);
         std::vector<double> d;
         for (const auto& l : dropcheck::slide_setups(s))
           d.push_back(dropcheck::slide_distance_continuous(l.v0, l.pull, l.mu * l.g, t));
         return agrees(m[1], d);
       }},
      {"slides " + N + " m in " + N + " steps",
       [](const Scene& s, const std::smatch& m) {
         const auto steps = static_cast<std::int64_t>(std::stod(m[2]));
         std::vector<double> d;
         for (const auto& l : dropcheck::slide_setups(s))
           d.push_back(dropcheck::slide_path(l, dropcheck::FrictionModel::cone, s.timestep.seconds,
                                             steps)
                           .s.back());
         return agrees(m[1], d);
       }},
      {"launched at " + N + " m/s",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> v;
         for (const auto& l : dropcheck::slide_setups(s)) v.push_back(l.v0);
         return agrees(m[1], v);
       }},
      {"at " + N + " degrees between x and z",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> a;
         for (const auto& l : dropcheck::slide_setups(s)) a.push_back(l.angle * 180.0 / M_PI);
         return agrees(m[1], a);
       }},
      {"friction mu = " + N,
       [](const Scene& s, const std::smatch& m) {
         const auto f = dropcheck::scene_material(s).friction;
         return agrees(m[1], f ? std::vector<double>{*f} : std::vector<double>{});
       }},
      {"at h = 1/" + N,
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], {1.0 / s.timestep.seconds});
       }},
      // Stability edge of a spring (harness/oracles/stability_theory.cpp: theory per damping order).
      {"stability edge h = " + N +
           " s(?: where damping (follows the forces|precedes the forces|"
           "follows the position update))?",
       [](const Scene& s, const std::smatch& m) {
         using dropcheck::DampingOrder;
         const std::string order = m[2];
         std::vector<DampingOrder> orders = {DampingOrder::AfterForces, DampingOrder::BeforeForces,
                                             DampingOrder::AfterPosition};
         if (order == "follows the forces") orders = {DampingOrder::AfterForces};
         if (order == "precedes the forces") orders = {DampingOrder::BeforeForces};
         if (order == "follows the position update") orders = {DampingOrder::AfterPosition};
         for (DampingOrder o : orders) {  // without an order named, every order must agree
           const auto edge = dropcheck::theory_max_dt(s, o);
           std::vector<double> values;
           if (edge) values.push_back(*edge);
           const std::string problem = agrees(m[1], values);
           if (!problem.empty()) return problem;
         }
         return std::string();
       }},
      // Float resolution at a coordinate.
      {"float spacing " + N + " m at [xyz] = " + N + " m",
       [](const Scene&, const std::smatch& m) {
         return agrees(m[1], {float_spacing(std::stod(m[2]))});
       }},
      // Landing (harness/oracles/landing.hpp): continuous-model first contact and rest height.
      {"first contact at t = " + N + " s",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], per_landing(s, &dropcheck::LandingSetup::contact_time));
       }},
      {"lands at " + N + " m/s",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> v;  // v(t_c) of the continuous model, by differentiating its height
         for (const auto& l : landing_setups(s)) {
           const Body& b = s.bodies[l.body];
           const double a = acceleration(s, l.body).y(), k = s.world.damping_rate;
           const double tc = l.contact_time;
           v.push_back(std::abs(k == 0.0 ? b.velocity.y() + a * tc
                                         : a / k + (b.velocity.y() - a / k) * std::exp(-k * tc)));
         }
         return agrees(m[1], v);
       }},
      {"rests at height " + N + " m",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], per_landing(s, &dropcheck::LandingSetup::rest_height));
       }},
      // Free flight (continuous model, harness/oracles/analytic.hpp).
      {"apex at t = " + N + " s",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> t;
         for (std::size_t i : thrown_up(s))
           t.push_back(
               apex_time(s.bodies[i].velocity.y(), acceleration(s, i).y(), s.world.damping_rate));
         return agrees(m[1], t);
       }},
      {"rises " + N + " m",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> rise;
         for (std::size_t i : thrown_up(s)) {
           const Body& b = s.bodies[i];
           const double a = acceleration(s, i).y(), k = s.world.damping_rate;
           const double t = apex_time(b.velocity.y(), a, k);
           rise.push_back(dropcheck::height_continuous(0.0, b.velocity.y(), a, k, t));
         }
         return agrees(m[1], rise);
       }},
      {"falls " + N + " m",
       [](const Scene& s, const std::smatch& m) {
         if (!dropcheck::analytic_unavailable(s).empty()) return agrees(m[1], {});
         return agrees(m[1], over_bodies(s, Which::any, [&](std::size_t i) {
                         return s.bodies[i].position.y() -
                                dropcheck::analytic_state(s, i, s.duration).position.y();
                       }));
       }},
      {"speed of " + N + " m/s at the end",
       [](const Scene& s, const std::smatch& m) {
         if (!dropcheck::analytic_unavailable(s).empty()) return agrees(m[1], {});
         return agrees(m[1], over_bodies(s, Which::any, [&](std::size_t i) {
                         return dropcheck::analytic_state(s, i, s.duration).velocity.norm();
                       }));
       }},
      {"terminal speed " + N + " m/s",
       [](const Scene& s, const std::smatch& m) {
         if (s.world.damping_rate == 0.0) return agrees(m[1], {});
         return agrees(m[1], over_bodies(s, Which::free, [&](std::size_t i) {
                         return acceleration(s, i).norm() / s.world.damping_rate;
                       }));
       }},
      {"net acceleration " + N + R"( m/s\^2)",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], over_bodies(s, Which::any,
                                         [&](std::size_t i) { return acceleration(s, i).norm(); }));
       }},
      // The world.
      {"gravity of " + N + R"( m/s\^2)",
       [](const Scene& s, const std::smatch& m) { return agrees(m[1], {s.world.gravity.norm()}); }},
      {"k = " + N + " 1/s",
       [](const Scene& s, const std::smatch& m) { return agrees(m[1], {s.world.damping_rate}); }},
      {N + " per step at " + N + " Hz",  // the seed's drag factor f = exp(-k*h) at h = 1/Hz
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], {std::exp(-s.world.damping_rate / std::stod(m[2]))});
       }},
      {"k\\*h from " + N + " to " + N,
       [](const Scene& s, const std::smatch& m) {
         return range_over_sweep(s, m, [&](double h) {
           return std::vector<double>{s.world.damping_rate * h};
         });
       }},
      // Steps and duration.
      {"h = " + N + " s",
       [](const Scene& s, const std::smatch& m) { return agrees(m[1], {s.timestep.seconds}); }},
      {"at " + N + " Hz",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> hz;
         for (double h : sweep_steps(s)) hz.push_back(1.0 / h);
         return agrees(m[1], hz);
       }},
      {N + " steps",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], {static_cast<double>(dropcheck::step_count(s, s.timestep.seconds))});
       }},
      // Rotation (harness/oracles/free_rotation.hpp for the torque-free tumble).
      {N + " kg box",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], over_bodies(s, Which::any,
                                         [&](std::size_t i) { return s.bodies[i].mass; }));
       }},
      {"sides " + N + " x " + N + " x " + N + " m",
       [](const Scene& s, const std::smatch& m) {
         for (int k = 0; k < 3; ++k) {
           const std::string problem = agrees(m[k + 1], over_bodies(s, Which::any, [&](std::size_t i) {
                                                return 2.0 * s.bodies[i].half_extents[k];
                                              }));
           if (!problem.empty()) return problem;
         }
         return std::string();
       }},
      {"(?:thrown|moving) at " + V + " m/s",
       [](const Scene& s, const std::smatch& m) {
         return agrees_vector(m, over_vectors(s, [](const Body& b) { return b.velocity; }));
       }},
      {"(?:spun|spinning|tumbling) at " + V + " rad/s",
       [](const Scene& s, const std::smatch& m) {
         return agrees_vector(m, over_vectors(s, [](const Body& b) { return b.angular_velocity; }));
       }},
      {"spinning at " + N + " rad/s about [xyz]",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], over_bodies(s, Which::any, [&](std::size_t i) {
                         return s.bodies[i].angular_velocity.norm();
                       }));
       }},
      {"flips every " + N + " s",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], over_bodies(s, Which::any, [&](std::size_t i) {
                         const Body& b = s.bodies[i];
                         const dropcheck::Vec3 w_body = b.orientation.conjugate() * b.angular_velocity;
                         return dropcheck::FreeRotation(dropcheck::inertia_of(b), w_body).period() / 2;
                       }));
       }},
      {"angular damping k_a = " + N + " 1/s",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], {s.world.angular_damping_rate});
       }},
      {"decays to " + N + " rad/s at " + N + " s",
       [](const Scene& s, const std::smatch& m) {
         const double t = std::stod(m[2]);
         return agrees(m[1], over_bodies(s, Which::any, [&](std::size_t i) {
                         return s.bodies[i].angular_velocity.norm() *
                                std::exp(-s.world.angular_damping_rate * t);
                       }));
       }},
      {"turns through " + N + " rad",
       [](const Scene& s, const std::smatch& m) {
         const double k = s.world.angular_damping_rate, t = s.duration;
         return agrees(m[1], over_bodies(s, Which::any, [&](std::size_t i) {
                         const double w = s.bodies[i].angular_velocity.norm();
                         return k == 0.0 ? w * t : w * -std::expm1(-k * t) / k;
                       }));
       }},
      {"runs for " + N + " s",
       [](const Scene& s, const std::smatch& m) { return agrees(m[1], {s.duration}); }},
      {"tolerance " + N + " m",
       [](const Scene& s, const std::smatch& m) { return agrees(m[1], {s.tolerance}); }},
      // Bodies and forces as the file sets them.
      {N + " kg cube",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> mass;
         for (const Body& b : s.bodies) mass.push_back(b.mass);
         return agrees(m[1], mass);
       }},
      {N + " times heavier",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> ratio;
         for (const Body& a : s.bodies)
           for (const Body& b : s.bodies)
             if (!a.is_static && !b.is_static) ratio.push_back(a.mass / b.mass);
         return agrees(m[1], ratio);
       }},
      {"from y = " + N + " m",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], over_bodies(s, Which::any,
                                         [&](std::size_t i) { return s.bodies[i].position.y(); }));
       }},
      {"at x = " + N + " m",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], over_bodies(s, Which::any,
                                         [&](std::size_t i) { return s.bodies[i].position.x(); }));
       }},
      {"thrown up at " + N + " m/s",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], over_bodies(s, Which::any,
                                         [&](std::size_t i) { return s.bodies[i].velocity.y(); }));
       }},
      {"(?:thrown|shot) down at " + N + " m/s",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], over_bodies(s, Which::any,
                                         [&](std::size_t i) { return -s.bodies[i].velocity.y(); }));
       }},
      {"(?:drifting|moving) at " + N + " m/s",
       [](const Scene& s, const std::smatch& m) {
         const auto speed = [&](std::size_t i) { return s.bodies[i].velocity.norm(); };
         return agrees(m[1], over_bodies(s, Which::any, speed));
       }},
      {"travels " + N + " m per step",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], over_bodies(s, Which::any, [&](std::size_t i) {
                         return s.bodies[i].velocity.norm() * s.timestep.seconds;
                       }));
       }},
      {"top at y = " + N + " m",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> top;
         for (const Body& b : s.bodies)
           if (b.is_static) top.push_back(b.position.y() + b.half_extents.y());
         return agrees(m[1], top);
       }},
      {"floor " + N + " m thick",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> thick;
         for (const Body& b : s.bodies)
           if (b.is_static) thick.push_back(2.0 * b.half_extents.y());
         return agrees(m[1], thick);
       }},
      {"force of " + N + " N",
       [](const Scene& s, const std::smatch& m) {
         std::vector<double> f;
         for (const dropcheck::Force& force : s.forces)
           if (const auto* c = std::get_if<dropcheck::ConstantForce>(&force.law))
             f.push_back(c->force.norm());
         return agrees(m[1], f);
       }},
      // Springs (rest length 0: linear oscillators).
      {"stiffness " + N + " N/m",
       [](const Scene& s, const std::smatch& m) {
         const auto stiffness = [&](std::size_t i) { return springs(s, i).S; };
         return agrees(m[1], over_bodies(s, Which::sprung, stiffness));
       }},
      {"dashpot of " + N + R"( N\*s/m)",
       [](const Scene& s, const std::smatch& m) {
         const auto dashpot = [&](std::size_t i) { return springs(s, i).C; };
         return agrees(m[1], over_bodies(s, Which::sprung, dashpot));
       }},
      {"omega = " + N + " rad/s",
       [](const Scene& s, const std::smatch& m) {
         const auto w = [&](std::size_t i) { return omega(s, i); };
         return agrees(m[1], over_bodies(s, Which::sprung, w));
       }},
      {"omega\\*h from " + N + " to " + N,
       [](const Scene& s, const std::smatch& m) {
         return range_over_sweep(s, m, [&](double h) {
           return over_bodies(s, Which::sprung, [&](std::size_t i) { return omega(s, i) * h; });
         });
       }},
      {"omega\\*h = " + N,
       [](const Scene& s, const std::smatch& m) {
         const auto wh = [&](std::size_t i) { return omega(s, i) * s.timestep.seconds; };
         return agrees(m[1], over_bodies(s, Which::sprung, wh));
       }},
      {"anchor " + N + " m above its start",
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], over_bodies(s, Which::sprung, [&](std::size_t i) {
                         return springs(s, i).A.y() - s.bodies[i].position.y();
                       }));
       }},
      {"sags " + N + " m",  // equilibrium x_eq = A + (m*g + F)/S, distance from the start
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], over_bodies(s, Which::sprung, [&](std::size_t i) {
                         const Springs sp = springs(s, i);
                         const Vec3 eq = sp.A + s.bodies[i].mass * acceleration(s, i) / sp.S;
                         return (eq - s.bodies[i].position).norm();
                       }));
       }},
      {N + " oscillations",  // duration * omega / (2*pi)
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], over_bodies(s, Which::sprung, [&](std::size_t i) {
                         return s.duration * omega(s, i) / (2.0 * M_PI);
                       }));
       }},
      // Semi-implicit Euler on an undamped oscillator turns by theta per step, with
      // 2*sin(theta/2) = w*h: its frequency is high by theta/(w*h) - 1 = (w*h)^2/24 + O(h^4).
      {"relative frequency error " + N,
       [](const Scene& s, const std::smatch& m) {
         return agrees(m[1], over_bodies(s, Which::sprung, [&](std::size_t i) {
                         const double wh = omega(s, i) * s.timestep.seconds;
                         return 2.0 * std::asin(wh / 2.0) / wh - 1.0;
                       }));
       }},
      // A cited section must exist.
      {"docs/engines\\.md section " + N,
       [](const Scene&, const std::smatch& m) {
         return engines_md_has_section(m[1]) ? std::string()
                                             : "cites docs/engines.md section " + m[1].str() +
                                                   ", which has no such section";
       }},
  };
  return list;
}

// Every problem of `scene`'s description: a figure that disagrees, or a digit outside any phrase.
// Phrases are matched in the order listed; a matched phrase is blanked out before the next.
std::vector<std::string> description_problems(const Scene& scene) {
  std::vector<std::string> problems;
  std::string text = scene.description;
  for (const Phrase& p : phrases()) {
    const std::regex re(p.pattern, std::regex::ECMAScript | std::regex::icase);
    std::string rest;
    std::smatch m;
    auto begin = text.cbegin();
    while (std::regex_search(begin, text.cend(), m, re)) {
      const std::string problem = p.check(scene, m);
      if (!problem.empty()) problems.push_back("\"" + m.str() + "\": " + problem);
      rest.append(begin, m[0].first).append("<checked>");
      begin = m[0].second;
    }
    text = rest.append(begin, text.cend());
  }
  text = std::regex_replace(text, std::regex("Box2D"), "<name>");  // a name, not a figure
  const std::regex digit("[^ ]*[0-9][^ ]*");
  for (std::sregex_iterator it(text.begin(), text.end(), digit), end; it != end; ++it)
    problems.push_back("\"" + it->str() +
                       "\": a figure in no checked phrase (tests/scenarios/descriptions_test.cpp)");
  return problems;
}

}  // namespace

TEST_CASE(
    "every figure in a shipped scene's description is one the harness computes from the scene",
    "[scenarios][descriptions]") {
  const std::vector<std::string> files = shipped_scenes();
  REQUIRE(files.size() >= 19);  // 7 scenes in scenarios/, 12 in scenarios/extreme/
  for (const std::string& file : files) {
    const Scene scene = dropcheck::load_scene(file);
    INFO(file << ": " << scene.description);
    CHECK_FALSE(scene.description.empty());
    for (const std::string& problem : description_problems(scene)) {
      INFO(problem);
      CHECK(problem.empty());  // prints the problem
    }
  }
}

TEST_CASE(
    "a description's figure that disagrees with its scene, or that no phrase checks, is refused",
    "[scenarios][descriptions]") {
  Scene s = dropcheck::load_scene(DROPCHECK_SOURCE_DIR "/scenarios/drop_on_floor.toml");
  s.description = "First contact at t = 1.9195 s, rests at height 0.5 m, k = 1.2122 1/s.";
  CHECK(description_problems(s).empty());
  s.description = "first contact at t = 1.5 s";  // the old description's figure: 1.9195 s
  REQUIRE(description_problems(s).size() == 1);
  CHECK_THAT(description_problems(s)[0], Catch::Contains("the scene gives 1.9195"));
  s.description = "first contact at t = 1.92 s";  // 1.91950 rounded: within half a unit of 1.92
  CHECK(description_problems(s).empty());
  s.description = "first contact at t = 1.9190 s";  // 1.919 with a digit more than is true
  CHECK(description_problems(s).size() == 1);
  s.description = "dropped from 10 m";  // a figure no phrase checks
  REQUIRE(description_problems(s).size() == 1);
  CHECK_THAT(description_problems(s)[0], Catch::Contains("no checked phrase"));
  s.description = "see docs/engines.md section 99";
  CHECK(description_problems(s).size() == 1);
}
