// Tests harness/oracles/identify_friction.cpp: the stop distances of each model's clamp law at 0
// and 45 degrees name that model, on a level floor and on a ramp; distances that fit no model, or
// a slide-less scene, are said.
#include "harness/oracles/identify_friction.hpp"

#include <catch2/catch.hpp>
#include <numbers>

#include "harness/core/input_error.hpp"
#include "harness/oracles/contact_laws.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/shipped_scenes.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;

TEST_CASE("each friction model's slides at 0 and 45 degrees name it", "[contact][identify]") {
  const Scene scene = testing::shipped("slide_diagonal");
  const double h = scene.timestep.seconds;
  for (FrictionModel m :
       {FrictionModel::cone, FrictionModel::box_pyramid, FrictionModel::sum_pyramid}) {
    const double d0 = slide_to_stop(5.0, 0.5, 9.8, h, m, 0.0).step_distance;
    const double d45 = slide_to_stop(5.0, 0.5, 9.8, h, m, std::numbers::pi / 4.0).step_distance;
    const FrictionIdentification id = identify_friction(scene, h, d0, d45);
    INFO(id.sentence());
    REQUIRE(id.named);
    CHECK(*id.named == m);
  }
  // The shipped slides' ratios: 1.762376/2.509472 and 3.566138/2.509472.
  const FrictionIdentification box = identify_friction(scene, h, 2.509472, 1.762376);
  CHECK(box.fits[1].ratio == Approx(0.70229).epsilon(1e-4));
  CHECK(box.fits[2].ratio == Approx(1.4211).epsilon(1e-4));
  // Both slides 8 mm short (a solver that stops early) still name the model: the ratio divides
  // it out to 0.3 %.
  CHECK(identify_friction(scene, h, 2.501472, 1.754376).named == FrictionModel::box_pyramid);
  // Between two models: none named.
  const FrictionIdentification between = identify_friction(scene, h, 2.509472, 2.1);
  CHECK_FALSE(between.named);
  CHECK_THAT(between.sentence(), Contains("NO MODEL"));
}

TEST_CASE(
    "the slide pair turns the scene's slide to 0 and 45 degrees; a scene without one is refused",
    "[contact][identify]") {
  const SlidePair pair = slide_pair(testing::shipped("slide_stop"));
  CHECK(slide_setups(pair.along_axis).at(0).angle == 0.0);
  CHECK(slide_setups(pair.diagonal).at(0).angle == Approx(std::numbers::pi / 4.0).epsilon(1e-15));
  CHECK(slide_setups(pair.diagonal).at(0).v0 == Approx(5.0).epsilon(1e-15));
  CHECK_FALSE(pair.pulled);
  CHECK_THROWS_AS(slide_pair(testing::shipped("free_fall")), InputError);
}

TEST_CASE("on a ramp the pull is turned, and the distances by the run's end name the model",
          "[contact][identify]") {
  // incline_slide (30 degrees, mu 0.5): each model's clamp law slides 2.970552 m along the axis;
  // at 45 degrees the cone as far, the box pyramid not at all (each axis holds its part of the
  // pull) and the sum pyramid 8.59 m.
  const Scene ramp = testing::shipped("incline_slide");
  const SlidePair pair = slide_pair(ramp);
  CHECK(pair.pulled);
  CHECK(pair.diagonal.world.gravity.x() == Approx(pair.diagonal.world.gravity.z()));
  CHECK(slide_setups(pair.diagonal).at(0).angle == Approx(std::numbers::pi / 4.0).epsilon(1e-12));
  const double h = ramp.timestep.seconds;
  const FrictionIdentification cone = identify_friction(ramp, h, 2.970552, 2.970552);
  CHECK(cone.named == FrictionModel::cone);
  CHECK(identify_friction(ramp, h, 2.970552, 6e-4).named == FrictionModel::box_pyramid);
  CHECK(identify_friction(ramp, h, 2.970552, 8.6).named == FrictionModel::sum_pyramid);
  CHECK_THAT(cone.sentence(), Contains("by the run's end"));
  // incline_hold (20 degrees, mu 0.5): held along the axis under every model; at 45 degrees the
  // sum pyramid's grip mu*g*cos/sqrt(2) is below the pull and it slides 0.434 m; the cone and the
  // box pyramid hold, and a held box cannot tell them apart.
  const Scene hold = testing::shipped("incline_hold");
  // A creep of 0.94 mm (MuJoCo's soft contact holds that way) is held.
  const FrictionIdentification held = identify_friction(hold, h, 0.0, 9.4e-4);
  CHECK(held.held);
  CHECK_FALSE(held.named);
  CHECK(held.fits[0].fits);
  CHECK(held.fits[1].fits);
  CHECK_FALSE(held.fits[2].fits);
  CHECK_THAT(held.sentence(), Contains("cone or box pyramid (this slide cannot tell them apart)"));
  CHECK(identify_friction(hold, h, 0.0, 0.434).named == FrictionModel::sum_pyramid);
  // A run that slides at 0 degrees where every model holds fits none.
  CHECK_FALSE(identify_friction(hold, h, 0.5, 0.434).fits[2].fits);
  // A ramp every model holds at 45 degrees too (3 degrees, mu 0.5): every model fits a held run.
  const Scene gentle = testing::shipped("friction/ramp_mu05_t03");
  const FrictionIdentification all = identify_friction(gentle, h, 0.0, 1e-3);
  CHECK_FALSE(all.named);
  for (const FrictionModelFit& f : all.fits) CHECK(f.fits);
  // A launched uphill slide keeps its pull's sign when turned.
  Scene uphill = testing::shipped("incline_slide");
  uphill.bodies[0].velocity = Vec3(-2.0, 0.0, 0.0);
  const SlidePair up = slide_pair(uphill);
  CHECK(up.diagonal.world.gravity.dot(up.diagonal.bodies[0].velocity) < 0.0);
}
