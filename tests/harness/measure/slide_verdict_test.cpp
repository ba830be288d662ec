// Tests harness/measure/slide_verdict.cpp: a run is judged against its friction model's clamp law,
// and a run that follows another model's law is named with it. The runs are the clamp laws
// themselves, written as trajectories, so no engine is needed.
#include "harness/measure/slide_verdict.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "harness/scene/scene_loader.hpp"

using namespace dropcheck;

namespace {

Scene shipped(const std::string& stem) {
  return load_scene(std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/" + stem + ".toml");
}

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
  const Scene scene = shipped("slide_diagonal");
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
  REQUIRE(wrong.instead.has_value());
  CHECK(*wrong.instead == FrictionModel::cone);
  CHECK_THAT(wrong.sentence(), Catch::Contains("stops at step 62, 2.509472 m") &&
                                   Catch::Contains("DEPARTS: it follows the cone's law instead"));
  const SlideVerdict sum = judge_slide(clamp_run(scene, slides[0], FrictionModel::sum_pyramid),
                                       slides[0], FrictionModel::sum_pyramid, h);
  CHECK(sum.follows);
  CHECK(sum.seen.stop_step == 87);
}

TEST_CASE("only a box launched along a floor it rests on is a slide", "[contact][slide]") {
  Scene scene = shipped("slide_stop");
  CHECK(slide_setups(scene).size() == 1);
  scene.bodies[0].position.y() += 0.01;  // hovering: a landing, not a slide
  CHECK(slide_setups(scene).empty());
  scene = shipped("slide_stop");
  scene.bodies[0].friction.reset();  // no friction set: the engines' defaults, no closed form
  CHECK(slide_setups(scene).empty());
  CHECK(slide_setups(shipped("drop_on_floor")).empty());
}
