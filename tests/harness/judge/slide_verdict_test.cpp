// Tests harness/judge/slide_verdict.cpp: a run is judged against its friction model's clamp law,
// and a run that follows another model's law is named with it. The runs are the clamp laws
// themselves, written as trajectories, so no engine is needed.
#include "harness/judge/slide_verdict.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "harness/scene/scene_loader.hpp"
#include "tests/shipped_scenes.hpp"

using namespace dropcheck;

namespace {

// The clamp law of `model` on `scene`'s slide, every step recorded: per tangent axis
// v <- max(v - a_i*h, 0), x += h*v (a_i as contact_laws.cpp: mu*g along the slip for the cone).
Trajectory clamp_run(const Scene& scene, const SlideSetup& s, FrictionModel model) {
  const double h = scene.timestep.seconds, mu_g = s.mu * s.g;
  const Body& b = scene.bodies[s.body];
  Vec3 x = b.position, v = b.velocity;
  const Vec3 dir = v.normalized();
  Trajectory t;
  t.h = h;
  t.steps = step_count(scene, h);
  for (const Body& body : scene.bodies) t.body_names.push_back(body.name);
  auto snapshot = [&](std::int64_t n) {
    t.recorded.push_back(n);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
      t.states.push_back(i == s.body ? BodyState{x, v} : BodyState{scene.bodies[i].position, {}});
  };
  snapshot(0);
  for (std::int64_t n = 1; n <= t.steps; ++n) {
    if (model == FrictionModel::cone) {
      const double speed = std::max(v.norm() - mu_g * h, 0.0);
      v = speed * dir;
    } else {
      const double a = model == FrictionModel::box_pyramid ? mu_g : mu_g / 2.0;
      for (int k : {0, 2}) v[k] = std::copysign(std::max(std::abs(v[k]) - a * h, 0.0), v[k]);
    }
    x += h * v;
    snapshot(n);
  }
  return t;
}

}  // namespace

TEST_CASE("a slide following its model's clamp law passes; another model's is named",
          "[contact][slide]") {
  const Scene scene = testing::shipped("slide_diagonal");
  const std::vector<SlideSetup> slides = slide_setups(scene);
  REQUIRE(slides.size() == 1);
  CHECK(slides[0].angle == Approx(std::numbers::pi / 4.0).margin(1e-15));
  CHECK(slides[0].v0 == Approx(5.0).epsilon(1e-15));
  const double h = scene.timestep.seconds;
  const SlideVerdict box = judge_slide(clamp_run(scene, slides[0], FrictionModel::box_pyramid),
                                       slides[0], FrictionModel::box_pyramid, h);
  CHECK(box.follows);
  CHECK(box.seen.stop_step == 44);
  // A cone engine that declared a box pyramid departs, and the cone is named.
  const SlideVerdict wrong = judge_slide(clamp_run(scene, slides[0], FrictionModel::cone),
                                         slides[0], FrictionModel::box_pyramid, h);
  CHECK_FALSE(wrong.follows);
  REQUIRE(wrong.instead_model.has_value());
  CHECK(*wrong.instead_model == FrictionModel::cone);
  CHECK(wrong.instead == "the cone's clamp law");
  CHECK_THAT(
      wrong.sentence(),
      Catch::Contains("stops at step 62, 2.509472 m") &&
          Catch::Contains(
              "DEPARTS at step 1 (first over 1e-06 m): it follows the cone's clamp law instead"));
  const SlideVerdict sum = judge_slide(clamp_run(scene, slides[0], FrictionModel::sum_pyramid),
                                       slides[0], FrictionModel::sum_pyramid, h);
  CHECK(sum.follows);
  CHECK(sum.seen.stop_step == 87);
}

namespace {

// A run whose sliding bodies move along their slips by `paths` (one per setup), the others still.
Trajectory path_run(const Scene& scene, const std::vector<SlideSetup>& setups,
                    const std::vector<SlidePath>& paths) {
  Trajectory t;
  t.h = scene.timestep.seconds;
  t.steps = static_cast<std::int64_t>(paths.front().s.size()) - 1;
  for (const Body& body : scene.bodies) t.body_names.push_back(body.name);
  for (std::int64_t n = 0; n <= t.steps; ++n) {
    t.recorded.push_back(n);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      BodyState b{scene.bodies[i].position, {}};
      for (std::size_t k = 0; k < setups.size(); ++k)
        if (setups[k].body == i) {
          const auto m = static_cast<std::size_t>(n);
          b.position += paths[k].s[m] * setups[k].direction;
          b.velocity = paths[k].v[m] * setups[k].direction;
        }
      t.states.push_back(b);
    }
  }
  return t;
}

}  // namespace

TEST_CASE("an incline: the held block must not creep, the launched one stops at its step",
          "[contact][slide]") {
  const Scene scene = testing::shipped("incline_hold");
  const std::vector<SlideSetup> slides = slide_setups(scene);
  REQUIRE(slides.size() == 2);
  CHECK(slides[0].v0 == 0.0);
  CHECK(slides[0].pull == Approx(9.8 * std::sin(20.0 * std::numbers::pi / 180.0)).epsilon(1e-15));
  const double h = scene.timestep.seconds;
  const std::int64_t steps = step_count(scene, h);
  std::vector<SlidePath> law;
  for (const SlideSetup& s : slides) law.push_back(slide_path(s, FrictionModel::cone, h, steps));
  const Trajectory exact = path_run(scene, slides, law);
  const SlideVerdict held = judge_slide(exact, slides[0], FrictionModel::cone, h);
  CHECK(held.follows);
  CHECK(held.seen.stop_step == 0);
  const SlideVerdict stopped = judge_slide(exact, slides[1], FrictionModel::box_pyramid, h);
  CHECK(stopped.follows);
  CHECK(stopped.seen.stop_step == 120);
  // A solver that lets the held block creep at 1e-5 m/s departs, naming where it ended.
  std::vector<SlidePath> creep = law;
  for (std::size_t n = 1; n < creep[0].s.size(); ++n) {
    creep[0].v[n] = 1e-5;
    creep[0].s[n] = creep[0].s[n - 1] + h * 1e-5;
  }
  const SlideVerdict crept =
      judge_slide(path_run(scene, slides, creep), slides[0], FrictionModel::cone, h);
  CHECK_FALSE(crept.follows);
  CHECK_THAT(crept.sentence(), Catch::Contains("slides on (3e-05 m by the end)") &&
                                   Catch::Contains("its cone's clamp law: never moves") &&
                                   Catch::Contains("DEPARTS"));
}

TEST_CASE("a slide's height is judged from where its contact put it after step 1",
          "[contact][slide]") {
  const Scene scene = testing::shipped("slide_stop");
  const std::vector<SlideSetup> slides = slide_setups(scene);
  const double h = scene.timestep.seconds;
  const SlidePath law = slide_path(slides[0], FrictionModel::cone, h, step_count(scene, h));
  Trajectory run = path_run(scene, slides, {law});
  const std::size_t bodies = scene.bodies.size();
  // A skin lifts the cube 0.015 m in step 1 and it slides on at that height: it follows.
  for (std::size_t n = 1; n < run.samples(); ++n) run.states[n * bodies].position.y() += 0.015;
  CHECK(judge_slide(run, slides[0], FrictionModel::cone, h).follows);
  // Sinking on after step 1, 1e-5 m a step: off its law by the height alone.
  for (std::size_t n = 2; n < run.samples(); ++n)
    run.states[n * bodies].position.y() -= 1e-5 * static_cast<double>(n - 1);
  const SlideVerdict sunk = judge_slide(run, slides[0], FrictionModel::cone, h);
  CHECK_FALSE(sunk.follows);
  CHECK(sunk.off_law == Approx(1e-5 * 239).epsilon(1e-9));
}

TEST_CASE("an incline steeper than the friction: the block slides at g*(sin - mu*cos)",
          "[contact][slide]") {
  const Scene scene = testing::shipped("incline_slide");
  const std::vector<SlideSetup> slides = slide_setups(scene);
  REQUIRE(slides.size() == 1);
  const double h = scene.timestep.seconds;
  const std::int64_t steps = step_count(scene, h);
  const SlidePath law = slide_path(slides[0], FrictionModel::cone, h, steps);
  const SlideVerdict v =
      judge_slide(path_run(scene, slides, {law}), slides[0], FrictionModel::sum_pyramid, h);
  CHECK(v.follows);
  CHECK(v.seen.stop_step == -1);
  CHECK(v.end_continuous == Approx(0.5 * 0.6564755214562492 * 9.0).epsilon(1e-12));
  // A solver whose friction grips 1 % less slides 0.19 m farther in 3 s (h^2*0.0424*180*181/2)
  // and departs.
  SlideSetup weaker = slides[0];
  weaker.mu *= 0.99;
  const SlideVerdict slipped =
      judge_slide(path_run(scene, slides, {slide_path(weaker, FrictionModel::cone, h, steps)}),
                  slides[0], FrictionModel::cone, h);
  CHECK_FALSE(slipped.follows);
  CHECK(slipped.off_law > 0.01);
}

TEST_CASE("a slide that is not free is not judged by the slide law", "[contact][slide]") {
  // Another cube on the slider: its normal force is 2*m*g, not m*g.
  Scene loaded = testing::shipped("slide_stop");
  Body top = loaded.bodies[0];
  top.name = "load";
  top.position.y() = 1.5;
  top.velocity = Vec3::Zero();
  loaded.bodies.push_back(top);
  CHECK(slide_setups(loaded).empty());
  // Drag takes speed off too.
  Scene damped = testing::shipped("slide_stop");
  damped.world.damping_rate = 0.1;
  CHECK(slide_setups(damped).empty());
  // A slide that would leave its floor: incline_slide's cube goes 2.970552 m in 180 steps (along
  // an axis every model grips mu*g; 3.0003 m with the 1 % margin): a floor 2.99 m long each way
  // cannot hold it, one 3.01 m long can.
  Scene short_floor = testing::shipped("incline_slide");
  short_floor.bodies[1].half_extents.x() = 2.99;
  CHECK(slide_setups(short_floor).empty());
  short_floor.bodies[1].half_extents.x() = 3.01;
  CHECK(slide_setups(short_floor).size() == 1);
}

TEST_CASE("only a box launched along a floor it rests on is a slide", "[contact][slide]") {
  Scene scene = testing::shipped("slide_stop");
  CHECK(slide_setups(scene).size() == 1);
  scene.bodies[0].position.y() += 0.01;  // hovering: a landing, not a slide
  CHECK(slide_setups(scene).empty());
  scene = testing::shipped("slide_stop");
  scene.bodies[0].friction.reset();  // no friction set: the engines' defaults, no closed form
  CHECK(slide_setups(scene).empty());
  CHECK(slide_setups(testing::shipped("drop_on_floor")).empty());
}

TEST_CASE("A replayed slide's departure is a limit only within 10 times its law's own",
          "[slide][contact]") {
  // The verdict's figures as judge_slide leaves them for a re-solved law that amplifies rounding.
  SlideVerdict v;
  v.solver = ContactSolver{};
  v.off_law = 7.5e-4;
  v.self_off = 2e-4;
  v.self_first = 1177;
  v.first_off = 998;
  CHECK(v.rounding_limited());
  CHECK_THAT(v.limit_text(), Catch::Contains("up to 0.0002 m, first at step 1177"));
  v.off_law = 2.1e-3;  // over 10 times: a fault, not the law's rounding
  CHECK_FALSE(v.rounding_limited());
  v.off_law = 7.5e-4;
  v.instead = "the cone's clamp law";  // another law fits: that is the cause
  CHECK_FALSE(v.rounding_limited());
  v.instead.clear();
  v.self_first = -1;  // the law holds to its own rounding: nothing excuses the departure
  CHECK_FALSE(v.rounding_limited());
  v.self_first = 1177;
  v.solver.reset();  // a clamp law is exact: its departures are never rounding
  CHECK_FALSE(v.rounding_limited());
}
