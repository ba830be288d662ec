// Helpers shared by the adapter tests (tests/adapters/*_test.cpp): the shipped free-flight scenes,
// the worst departure of a run from its engine's law, a drop-on-floor scene built in code and how
// an engine lands on it, and the checks every adapter test repeats (its law in free flight, the
// docs/engines.md drag figure, the masses of scenarios/wind.toml).
#pragma once

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "harness/core/registry.hpp"
#include "harness/core/trajectory.hpp"
#include "harness/judge/bounce_verdict.hpp"
#include "harness/judge/slide_verdict.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/oracles/replayed_contact.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/shipped_scenes.hpp"

// Declares `engine` as make_engine(name), or warns why that engine is unavailable and ends the test
// case (for the engines a build may leave out).
#define ENGINE_OR_RETURN(engine, name)                                  \
  auto engine = ::dropcheck::make_engine(name);                         \
  if (!engine) {                                                        \
    WARN(name << ": " << ::dropcheck::engine_unavailable_reason(name)); \
    return;                                                             \
  }

namespace dropcheck::testing {

inline const char* const kFreeFlightScenes[] = {"seed_part3", "free_fall", "free_fall_drag", "wind",
                                                "throw_up"};

inline Scene scenario(const std::string& name) {
  return shipped(name);
}

// The largest position difference between a run and its engine's law, and where it occurs.
struct WorstDx {
  double dx = 0.0;
  std::string where = "nowhere";
};

inline WorstDx worst_dx(const Trajectory& run, const Trajectory& law) {
  WorstDx w;
  for (std::size_t s = 0; s < run.samples(); ++s) {
    for (std::size_t b = 0; b < run.bodies(); ++b) {
      const double dx = (run.at(s, b).position - law.at(s, b).position).norm();
      if (dx <= w.dx) continue;
      std::ostringstream m;
      m.precision(17);
      m << "scene " << run.scene << ", engine " << run.engine << ", body " << run.body_names[b]
        << ", step " << run.recorded[s] << " (h = " << run.h << "): engine x = ("
        << run.at(s, b).position.transpose() << "), law x = (" << law.at(s, b).position.transpose()
        << "), |dx| = " << dx;
      w = {dx, m.str()};
    }
  }
  return w;
}

// A unit cube whose centre starts at 10 m above a static floor box whose top is at y = 0; no drag
// (the hardest landing: 13.6 m/s), as scenarios/drop_on_floor_undamped.toml.
inline Scene drop_on_floor() {
  Scene s;
  s.name = "drop_on_floor (in code)";
  s.duration = 5.0;
  s.world.gravity = Vec3(0.0, -9.8, 0.0);
  s.world.contacts = true;
  s.bodies.push_back({.name = "floor",
                      .half_extents = {10.0, 0.5, 10.0},
                      .position = {0.0, -0.5, 0.0},
                      .is_static = true});
  s.bodies.push_back({.name = "cube", .position = {0.0, 10.0, 0.0}});
  return s;
}

// Checks that engine `name` declares `law`, which the conformance suite checks it against (warns
// and returns when `name` is not built).
inline void check_declared_law(const std::string& name, const Law& law) {
  ENGINE_OR_RETURN(engine, name);
  INFO(name << " declares " << to_string(engine->info().law));
  CHECK(engine->info().law == law);
}

// make_engine(name), required to exist (for a test file built only with that engine).
inline std::unique_ptr<Engine> required_engine(const std::string& name) {
  auto e = make_engine(name);
  REQUIRE(e);
  return e;
}

// Checks `engine` against its own discrete law in every free-flight scene at the scene's step,
// 1/30 and 1/240: the worst |dx| of a run of `steps` steps must be at most tolerance(steps).
inline void check_free_flight_law(Engine& engine,
                                  const std::function<double(std::int64_t steps)>& tolerance) {
  for (const char* name : kFreeFlightScenes) {
    const Scene scene = scenario(name);
    for (const double h : {scene.timestep.seconds, 1.0 / 30.0, 1.0 / 240.0}) {
      const Trajectory run = run_scene(engine, scene, h);
      REQUIRE(run.status == RunStatus::ok);
      const WorstDx w = worst_dx(run, predict_discrete(engine.info().law, scene, h));
      INFO(w.where);
      CHECK(w.dx <= tolerance(run.steps));
    }
  }
}

// docs/engines.md's drag figure: 60 steps of h = 1/60, g = -9.8, f = 0.98, x0 = 10, v0 = 0, m = 1
// (scenarios/free_fall_drag), required to have all 60 steps.
inline Trajectory drag_figure_run(Engine& engine) {
  const Trajectory run = run_scene(engine, scenario("free_fall_drag"), 1.0 / 60.0);
  REQUIRE(run.recorded.back() == 60);
  return run;
}

// Checks that `engine` gives the bodies of scenarios/wind.toml their masses, 3.375 kg (a 1.5 m
// cube of density 1) and 1 kg, with and without contacts; `mass` reads body i of the loaded engine.
inline void check_wind_masses(Engine& engine,
                              const std::function<double(const Engine&, std::size_t)>& mass) {
  Scene scene = scenario("wind");
  for (const bool contacts : {false, true}) {
    scene.world.contacts = contacts;
    engine.load(scene, 1.0 / 60.0);
    INFO("contacts = " << contacts);
    CHECK(mass(engine, 0) == 3.375);
    CHECK(mass(engine, 1) == 1.0);
  }
}

// Landing of body `cube` as seen in a run, measured against the same scene without contacts.
struct Landing {
  std::int64_t touch_step = -1;  // first step whose state has the cube's bottom at or below y = 0
  std::int64_t response_step = -1;  // first step whose state departs from free flight
  double lowest = 1e300;            // lowest centre height
  double highest_after = -1e300;    // highest centre height from the response on (rebound)
  double rest = 0.0;                // final centre height
  double settled_at = 0.0;          // from then on |v| <= 1e-3 m/s and |y - rest| <= 1e-4 m
};

// The Landing of body `cube` of a unit cube over a floor whose top is y = 0; a state departs from
// free flight (`free`) when its height differs by more than `departs` m.
inline Landing measure_landing(const Trajectory& run, const Trajectory& free, std::size_t cube,
                               double departs) {
  Landing l;
  l.rest = run.final_state(cube).position.y();
  for (std::size_t s = 0; s < run.samples(); ++s) {
    const BodyState& b = run.at(s, cube);
    const double y = b.position.y();
    if (l.touch_step < 0 && y <= 0.5) l.touch_step = run.recorded[s];
    if (l.response_step < 0 && std::abs(y - free.at(s, cube).position.y()) > departs)
      l.response_step = run.recorded[s];
    if (l.response_step >= 0) l.highest_after = std::max(l.highest_after, y);
    l.lowest = std::min(l.lowest, y);
    if (b.velocity.norm() > 1e-3 || std::abs(y - l.rest) > 1e-4)
      l.settled_at = run.time(std::min(s + 1, run.samples() - 1));
  }
  return l;
}

// A run of drop_on_floor() at 1/60 and how the cube landed, with what the references need.
struct DropLanding {
  EngineInfo info;  // the engine's declarations (rest_offset, rest_tolerance)
  double h = 1.0 / 60.0;
  // Continuous model: the bottom reaches y = 0 after a fall of 9.5 m at t_c = sqrt(2*9.5/9.8),
  // 1.3924 s, inside step 84.
  double t_c = std::sqrt(2.0 * 9.5 / 9.8);
  Landing l;  // measured against the engine's own law without contacts
};

// Runs drop_on_floor() on `engine` (required to finish) and measures its landing (see
// measure_landing for `departs`).
inline DropLanding land_drop_on_floor(Engine& engine, double departs) {
  DropLanding d;
  const Scene scene = drop_on_floor();
  d.info = engine.info();
  const Trajectory run = run_scene(engine, scene, d.h);
  REQUIRE(run.status == RunStatus::ok);
  d.l = measure_landing(run, predict_discrete(d.info.law, scene, d.h), 1, departs);
  return d;
}

// One shipped bounce scene as an engine runs it: the figures its test pins.
struct BounceCase {
  const char* scene;
  double worst;      // m: the measured largest departure from the engine's bounce law
  double speed_out;  // m/s: the rebound after the contact step
  double apex;       // m: the first apex (ignored when <= -1)
};

// Runs each case on `engine` and checks that it follows its declared bounce law
// (harness/judge/bounce_verdict.hpp): within tolerance and within 1.5x the measured departure,
// contact at step 27 at 4.41 m/s (every shipped bounce falls 1 m at 1/60), the rebound and apex.
inline void check_bounces(Engine& engine, std::initializer_list<BounceCase> cases) {
  for (const BounceCase& c : cases) {
    INFO(c.scene);
    const Scene scene = scenario(c.scene);
    const BounceSetup s = bounce_setups(scene).at(0);
    const Trajectory run = run_scene(engine, scene, scene.timestep.seconds);
    REQUIRE(run.status == RunStatus::ok);
    const BounceVerdict v = judge_bounce(run, s, engine.info().bounce_law, scene.timestep.seconds);
    INFO(v.sentence());
    CHECK(v.follows);
    CHECK(v.worst_gap <= 1.5 * c.worst);
    CHECK(v.seen.contact_step == 27);
    CHECK(v.seen.speed_in == Approx(4.41).epsilon(1e-12));
    CHECK(v.seen.speed_out == Approx(c.speed_out).epsilon(1e-7));
    if (c.apex > -1.0) CHECK(v.seen.apexes.at(0) == Approx(c.apex).epsilon(1e-6));
  }
}

// A slide run by engine `name` on `scene` and judged against its own law for `judged_as` (the
// scene itself, or the scene a mistaken run should have followed): its slide number `slide`
// (slide_setups' order).
struct JudgedSlide {
  Trajectory run;
  SlideVerdict verdict;
};

inline JudgedSlide judged_slide(const std::string& name, const Scene& scene, const Scene& judged_as,
                                bool body_materials = false, std::size_t slide = 0) {
  std::unique_ptr<Engine> engine = required_engine(name);
  if (body_materials) REQUIRE(engine->use_body_materials());
  const double h = scene.timestep.seconds;
  JudgedSlide j{run_scene(*engine, scene, h), {}};
  REQUIRE(j.run.status == RunStatus::ok);
  j.verdict = judge_slide(j.run, judged_as, slide_setups(judged_as).at(slide), engine->info(), h);
  return j;
}

// Checks that engine `name` (a replayed solver) moves each slide of each of `scenes` as its replay
// does, to `max_off` m (0: bit for bit, the same operations in the same order), and that the last
// slide of each (the launched one, where a scene also holds a body at rest) departs from it by step
// 2 when the friction is 2 % off. The default scenes are the planar slides.
inline void check_replayed_slides(const std::string& name,
                                  std::initializer_list<const char*> scenes = {"slide_stop",
                                                                               "incline_slide",
                                                                               "incline_hold"},
                                  double max_off = 0.0) {
  for (const char* scene_name : scenes) {
    const Scene scene = scenario(scene_name);
    const std::size_t slides = slide_setups(scene).size();
    for (std::size_t k = 0; k < slides; ++k) {
      const SlideVerdict v = judged_slide(name, scene, scene, false, k).verdict;
      INFO(scene_name << ", slide " << k << ": " << v.sentence());
      CHECK(v.exact);
      CHECK(v.solver.has_value());
      CHECK(v.follows);
      CHECK(v.off_law <= max_off);
    }
    Scene off = scene;
    for (Body& b : off.bodies)
      if (b.friction) *b.friction *= 1.02;
    const SlideVerdict d = judged_slide(name, off, scene, false, slides - 1).verdict;
    INFO(scene_name << ", mu 2 % off: " << d.sentence());
    CHECK_FALSE(d.follows);
    CHECK(d.first_off >= 1);
    CHECK(d.first_off <= 2);  // the first steps with friction already differ
    CHECK_THAT(d.sentence(), Catch::Contains("DEPARTS at step"));
  }
}

// The slide of slide_stop run by engine `name` with each body's friction given by `friction` (its
// own material: the engine's combine rule makes the pair's), judged against the shipped scene.
inline SlideVerdict slide_with_materials(const std::string& name,
                                         const std::function<double(const Body&)>& friction) {
  const Scene scene = scenario("slide_stop");
  Scene materials = scene;
  for (Body& b : materials.bodies) b.friction = friction(b);
  return judged_slide(name, materials, scene, true).verdict;
}

// A bounce run by engine `name` on `scene`, judged against its own law for `judged_as`.
inline BounceVerdict judged_bounce(const std::string& name, const Scene& scene,
                                   const Scene& judged_as) {
  std::unique_ptr<Engine> engine = required_engine(name);
  const double h = scene.timestep.seconds;
  const Trajectory run = run_scene(*engine, scene, h);
  REQUIRE(run.status == RunStatus::ok);
  return judge_bounce(run, judged_as, bounce_setups(judged_as).at(0), engine->info(), h);
}

// Checks that engine `name` (a replayed solver) bounces on each shipped bounce scene as its replay
// does, to `max_gap` m (0: bit for bit), and departs from it when the restitution is 2 % off.
inline void check_replayed_bounces(const std::string& name, double max_gap = 0.0) {
  for (const char* scene_name : {"bounce_e01", "bounce_e05", "bounce_e09"}) {
    const Scene scene = scenario(scene_name);
    const BounceVerdict v = judged_bounce(name, scene, scene);
    INFO(scene_name << ": " << v.sentence());
    CHECK(v.solver.has_value());
    CHECK(v.not_judged.empty());
    CHECK(v.follows);
    CHECK(v.worst_gap <= max_gap);
    Scene off = scene;
    for (Body& b : off.bodies)
      if (b.restitution) *b.restitution *= 1.02;
    const BounceVerdict d = judged_bounce(name, off, scene);
    INFO("e 2 % off: " << d.sentence());
    CHECK_FALSE(d.follows);
    CHECK_THAT(d.sentence(), Catch::Contains("DEPARTS at step"));
  }
}

// What a random contact scene may hold: the default is a replay's planar scope.
struct RandomContact {
  bool planar = true;       // x-y only; else gravity, size and velocity along z too
  bool spheres = true;      // half the bodies are spheres
  bool restitution = true;  // a random restitution
};

// A random contact scene: one dynamic box or sphere thrown over a static floor box under a tilted
// gravity, its friction (and restitution), and a step of 1/30, 1/60 or 1/240 s (seeded: the same
// scenes every run).
inline Scene random_contact_scene(std::mt19937& rng, RandomContact what = {}) {
  const auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  Scene s;
  s.name = "random contact";
  s.duration = 2.0;
  const int per_second[] = {30, 60, 240};
  const int n = per_second[std::uniform_int_distribution<int>(0, 2)(rng)];
  s.timestep = {1.0 / n, "1/" + std::to_string(n)};
  s.timesteps = {s.timestep};
  s.world.gravity = Vec3(uniform(-3.0, 3.0), -9.8, what.planar ? 0.0 : uniform(-3.0, 3.0));
  s.world.contacts = true;
  Body body{.name = "body", .mass = uniform(0.2, 5.0)};
  if (what.spheres && uniform(0.0, 1.0) < 0.5) {
    body.shape = Shape::sphere;
    body.radius = uniform(0.1, 1.0);
    body.half_extents = Vec3::Constant(body.radius);
  } else {
    body.half_extents.x() = uniform(0.1, 1.0);
    body.half_extents.y() = uniform(0.1, 1.0);
    body.half_extents.z() = what.planar ? 0.5 : uniform(0.1, 1.0);
  }
  body.position = Vec3(uniform(-2.0, 2.0), body.half_extents.y() + uniform(0.0, 3.0), 0.0);
  body.velocity.x() = uniform(-6.0, 6.0);
  body.velocity.y() = uniform(-6.0, 3.0);
  body.velocity.z() = what.planar ? 0.0 : uniform(-6.0, 6.0);
  body.friction = uniform(0.0, 1.0);
  if (what.restitution) body.restitution = uniform(0.0, 1.0);
  s.bodies.push_back(body);
  s.bodies.push_back({.name = "floor",
                      .half_extents = {20.0, 0.5, 20.0},
                      .position = {0.0, -0.5, 0.0},
                      .is_static = true,
                      .friction = body.friction,
                      .restitution = body.restitution});
  return s;
}

// Checks that engine `name`, whose contact solver the harness replays, moves like its replay bit
// for bit at every step of `count` random contact scenes.
inline void check_replay_on_random_scenes(const std::string& name, int count) {
  std::mt19937 rng(20261127);
  for (int k = 0; k < count; ++k) {
    const Scene scene = random_contact_scene(rng);
    std::unique_ptr<Engine> engine = required_engine(name);
    const double h = scene.timestep.seconds;
    const Trajectory run = run_scene(*engine, scene, h);
    REQUIRE(run.status == RunStatus::ok);
    const std::vector<BodyState> law = replayed_states(
        scene, 0, engine->info().contact_solver, h, static_cast<std::int64_t>(run.samples()) - 1);
    REQUIRE(law.size() == run.samples());
    std::size_t first = run.samples();
    for (std::size_t i = 0; i < run.samples() && first == run.samples(); ++i)
      if (run.at(i, 0).position != law[i].position || run.at(i, 0).velocity != law[i].velocity)
        first = i;
    INFO("scene " << k << " at h = " << scene.timestep.text << ": first differs at sample "
                  << first);
    CHECK(first == run.samples());
  }
}

}  // namespace dropcheck::testing
