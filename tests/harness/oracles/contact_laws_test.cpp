// Tests harness/oracles/contact_laws.cpp against the closed forms and the figures the Contact issue
// states (each recomputed independently: docs/contact.md gives the arithmetic).
#include "harness/oracles/contact_laws.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "harness/oracles/landing.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/scene_texts.hpp"

using dropcheck::bounce;
using dropcheck::bounce_path;
using dropcheck::BouncePath;
using dropcheck::FrictionModel;
using dropcheck::kIdealBounce;
using dropcheck::observe_bounce;
using dropcheck::slide_to_stop;

namespace {
constexpr double kG = 9.8, kH = 1.0 / 60.0, kDiagonal = std::numbers::pi / 4.0;
}

TEST_CASE("slide to stop: a unit cube at 5 m/s with mu = 0.5 stops after 2.5510 m in 1.0204 s",
          "[contact][reference]") {
  const auto s = slide_to_stop(5.0, 0.5, kG, kH, FrictionModel::cone, 0.0);
  CHECK(s.deceleration == Approx(4.9).epsilon(1e-15));
  CHECK(s.stop_time == Approx(5.0 / 4.9).epsilon(1e-15));  // 1.0204 s
  CHECK(s.distance == Approx(25.0 / 9.8).epsilon(1e-15));  // 2.5510 m
  // The clamp v <- max(v - mu*g*h, 0): 61 steps leave 0.0183 m/s, the 62nd stops it; the body
  // moved h*(61*5 - 0.081667*61*62/2) = 2.509472 m.
  CHECK(s.stop_step == 62);
  CHECK(s.step_distance == Approx(2.509472222222222).epsilon(1e-12));
}

TEST_CASE(
    "slide at 45 degrees: the cone as straight, the box pyramid sqrt(2) shorter, the sum "
    "pyramid sqrt(2) longer",
    "[contact][reference]") {
  const auto cone = slide_to_stop(5.0, 0.5, kG, kH, FrictionModel::cone, kDiagonal);
  const auto box = slide_to_stop(5.0, 0.5, kG, kH, FrictionModel::box_pyramid, kDiagonal);
  const auto sum = slide_to_stop(5.0, 0.5, kG, kH, FrictionModel::sum_pyramid, kDiagonal);
  CHECK(cone.stop_step == 62);
  CHECK(cone.step_distance == Approx(2.509472222222222).epsilon(1e-12));
  CHECK(box.stop_step == 44);
  CHECK(box.step_distance == Approx(1.7623762369377096).epsilon(1e-12));
  CHECK(sum.stop_step == 87);
  CHECK(sum.step_distance == Approx(3.5661378624298647).epsilon(1e-12));
  // Continuous: the ratios identify the model (1, 1/sqrt(2), sqrt(2)).
  CHECK(box.distance / cone.distance == Approx(1.0 / std::sqrt(2.0)).epsilon(1e-14));
  CHECK(sum.distance / cone.distance == Approx(std::sqrt(2.0)).epsilon(1e-14));
  // Along an axis every model is the cone.
  const auto along = slide_to_stop(5.0, 0.5, kG, kH, FrictionModel::sum_pyramid, 0.0);
  CHECK(along.stop_step == 62);
  CHECK_THROWS_AS(slide_to_stop(5.0, 0.5, kG, kH, FrictionModel::box_pyramid, 0.3),
                  std::invalid_argument);
  CHECK_THROWS_AS(slide_to_stop(5.0, 0.0, kG, kH, FrictionModel::cone, 0.0), std::invalid_argument);
}

TEST_CASE("incline: a block holds when tan(theta) <= mu, and slides at g*(sin - mu*cos) otherwise",
          "[contact][reference]") {
  using dropcheck::observe_slide;
  using dropcheck::slide_distance_continuous;
  using dropcheck::slide_path;
  using dropcheck::SlideSetup;
  const auto cone = FrictionModel::cone;
  const double t20 = 20.0 * std::numbers::pi / 180.0, t30 = 30.0 * std::numbers::pi / 180.0;
  // 20 degrees: the pull 9.8*sin 20 = 3.3518 is within mu*9.8*cos 20 = 4.6045; a block at rest
  // never moves.
  const double g20 = kG * std::cos(t20), pull20 = kG * std::sin(t20);
  const auto hold = slide_to_stop(0.0, 0.5, g20, kH, cone, 0.0, pull20);
  CHECK(hold.stops);
  CHECK(hold.stop_step == 0);
  // Launched down the slope at 2.5 m/s it decelerates at mu*g*cos - g*sin = 1.2527 m/s^2: stops
  // after 1.9957 s and 2.4946 m; the discrete law after ceil(2.5/(1.2527*h)) = ceil(119.74) = 120
  // steps, h*(119*2.5 - 1.2527*h*119*120/2) = 2.473819 m.
  const auto down = slide_to_stop(2.5, 0.5, g20, kH, cone, 0.0, pull20);
  const double a = 0.5 * g20 - pull20;
  CHECK(down.deceleration == Approx(1.2526964372593978).epsilon(1e-14));
  CHECK(down.stop_time == Approx(2.5 / a).epsilon(1e-14));
  CHECK(down.distance == Approx(2.5 * 2.5 / (2.0 * a)).epsilon(1e-14));
  CHECK(down.stop_step == 120);
  CHECK(down.step_distance == Approx(kH * (119 * 2.5 - a * kH * 119 * 120 / 2.0)).epsilon(1e-13));
  // The stepped law agrees with the closed-form step count, and holds the block after its stop.
  const SlideSetup launched{0, 2.5, {1.0, 0.0, 0.0}, 0.0, 0.5, g20, pull20};
  const auto path = slide_path(launched, cone, kH, 180);
  const auto seen = observe_slide(path, 1e-6, 1e-6);
  CHECK(seen.stop_step == 120);
  CHECK(seen.distance == Approx(down.step_distance).epsilon(1e-13));
  CHECK(path.s[180] == path.s[120]);
  // 30 degrees: tan 30 = 0.577 > mu: from rest it accelerates at 9.8*(sin 30 - 0.5*cos 30) =
  // 0.65648 m/s^2; continuous a*t^2/2 = 2.9541 m in 3 s; discrete h*sum(n*a*h) =
  // h^2*a*180*181/2 = 2.970552 m in 180 steps.
  const double g30 = kG * std::cos(t30), pull30 = kG * std::sin(t30), a30 = pull30 - 0.5 * g30;
  CHECK(a30 == Approx(0.6564755214562492).epsilon(1e-14));
  const auto slides = slide_to_stop(0.0, 0.5, g30, kH, cone, 0.0, pull30);
  CHECK_FALSE(slides.stops);
  CHECK(slides.stop_step == -1);
  CHECK(slide_distance_continuous(0.0, pull30, 0.5 * g30, 3.0) == Approx(a30 * 4.5).epsilon(1e-14));
  const SlideSetup released{0, 0.0, {1.0, 0.0, 0.0}, 0.0, 0.5, g30, pull30};
  const auto free_path = slide_path(released, cone, kH, 180);
  CHECK(free_path.s[180] == Approx(kH * kH * a30 * 180 * 181 / 2.0).epsilon(1e-12));
  CHECK(free_path.s[180] == Approx(2.970551734589528).epsilon(1e-12));
  CHECK(observe_slide(free_path, 1e-6, 1e-6).stop_step == -1);
  // A path that reports no speed while its position creeps has not stopped where its speed did:
  // the stop is the first step from which the position stays within `settled` too.
  dropcheck::SlidePath creeping = path;
  for (std::size_t n = 121; n < creeping.s.size(); ++n)
    creeping.s[n] = path.s[120] + 1e-3 * (n - 120.0);
  CHECK(observe_slide(creeping, 1e-6, INFINITY).stop_step == 120);  // the speed alone: stopped
  const auto crept = observe_slide(creeping, 1e-6, 1e-6);
  CHECK(crept.stop_step == 180);
  CHECK(crept.distance == Approx(path.s[120] + 0.06).epsilon(1e-12));
  // Launched up the 30 degree slope at 2 m/s: it climbs at grip + pull = 9.1435 m/s^2 of
  // deceleration to v0^2/(2*9.1435), then slides back at pull - grip = 0.65648 m/s^2.
  const double up = 0.5 * g30 + pull30, t_up = 2.0 / up;
  CHECK(slide_distance_continuous(2.0, -pull30, 0.5 * g30, t_up + 1.0) ==
        Approx(2.0 * 2.0 / (2.0 * up) - 0.5 * a30).epsilon(1e-14));
  const SlideSetup uphill{0, 2.0, {1.0, 0.0, 0.0}, 0.0, 0.5, g30, -pull30};
  const auto back = slide_path(uphill, cone, kH, 180);
  CHECK(back.v[180] < 0.0);  // sliding back down
  CHECK(back.s[180] ==
        Approx(slide_distance_continuous(2.0, -pull30, 0.5 * g30, 3.0)).epsilon(0.02));
}

TEST_CASE("bounce: apexes e^(2n)*h0, flights 2*e^n*sqrt(2*h0/g), rest after 1.3553 s at e = 0.5",
          "[contact][reference]") {
  for (const double e : {0.1, 0.5, 0.9}) {
    const auto b = bounce(1.0, e, kG, kH);
    INFO("e = " << e);
    REQUIRE(b.apexes.size() == 3);
    for (int n = 1; n <= 3; ++n) {
      CHECK(b.apexes[n - 1] == Approx(std::pow(e, 2 * n)).epsilon(1e-14));
      CHECK(b.flights[n - 1] == Approx(2.0 * std::pow(e, n) * std::sqrt(2.0 / kG)).epsilon(1e-14));
    }
    // Energy never rises: each apex is below the last.
    CHECK(b.apexes[1] < b.apexes[0]);
    CHECK(b.time_to_rest == Approx(std::sqrt(2.0 / kG) * (1 + e) / (1 - e)).epsilon(1e-14));
  }
  CHECK(bounce(1.0, 0.5, kG, kH).time_to_rest == Approx(1.3552618543578767).epsilon(1e-14));
  CHECK(std::isinf(bounce(1.0, 1.0, kG, kH).time_to_rest));
  CHECK_THROWS_AS(bounce(1.0, 1.5, kG, kH), std::invalid_argument);
}

TEST_CASE(
    "bounce, discrete: a sphere falling 1 m at h = 1/60 hits at step 27 at 4.41 m/s and "
    "leaves at 2.205 m/s",
    "[contact][reference]") {
  const auto b = bounce(1.0, 0.5, kG, kH);
  // After n steps the drop is g*h^2*n*(n + 1)/2: 0.9556 m at 26, 1.029 m at 27.
  CHECK(b.contact_step == 27);
  CHECK(b.step_speed_in == Approx(4.41).epsilon(1e-14));
  CHECK(b.step_speed_out == Approx(2.205).epsilon(1e-14));
  // It left from where step 27 ended, 0.029 m in the floor (1 - g*h^2*27*28/2 = -0.0290), and
  // climbs 14 steps: -0.0290 + h*(14*2.205 - g*h*91) = 0.23778 m, the 0.2378 (the
  // continuous climb from 2.205 m/s is 2.205^2/(2*g) = 0.248).
  const double ended = 1.0 - kG * kH * kH * 27 * 28 / 2;
  CHECK(ended == Approx(-0.029).epsilon(1e-12));
  CHECK(b.step_apex == Approx(ended + (14 * 2.205 - kG * kH * 91) * kH).epsilon(1e-12));
  CHECK(b.step_apex == Approx(0.23777777777777).epsilon(1e-10));
}

TEST_CASE("bounce paths: the push-out and threshold members change what the ideal law predicts",
          "[contact][reference]") {
  const std::int64_t steps = 180;
  // e = 0.1: the rebound at 0.441 m/s leaves the sphere in the floor, 0.029 m deep after step 27.
  const BouncePath ideal = bounce_path(kIdealBounce, 1.0, 0.1, kG, kH, steps);
  const BouncePath ode = bounce_path({.erp = 0.2, .max_push = 0.3}, 1.0, 0.1, kG, kH, steps);
  const auto oi = observe_bounce(ideal.gap, ideal.v, kG, kH);
  const auto oo = observe_bounce(ode.gap, ode.v, kG, kH);
  CHECK(oi.contact_step == 27);
  CHECK(oo.contact_step == 27);
  CHECK(oi.speed_out == Approx(0.441).epsilon(1e-12));
  CHECK(oo.speed_out == Approx(0.441).epsilon(1e-12));  // e*v beats 0.2*0.029*60 = 0.348
  // The ideal law climbs three steps (0.441, 0.441 - g*h, 0.441 - 2*g*h) and stops in the floor,
  // the contact holding it at v = 0: its apex is -0.0151 m.
  const double ended = 1.0 - kG * kH * kH * 27 * 28 / 2;
  REQUIRE(oi.apexes.size() == 1);
  CHECK(oi.apexes.front() == Approx(ended + kH * (3 * 0.441 - 3 * kG * kH)).epsilon(1e-12));
  CHECK(ideal.gap[steps] == oi.apexes.front());
  // With the push-out, step 29 (from -0.021650 m) keeps v_free = 0.27767 over 0.2*0.021650*60 =
  // 0.25980; step 30 (from -0.017022 m) takes the push-out 0.20427 over v_free = 0.11433, and from
  // there each step pushes out a fifth of the depth: the sphere returns to the surface, no apex.
  CHECK(ode.v[29] == Approx(0.441 - kG * kH).epsilon(1e-12));
  CHECK(ode.v[30] == Approx(0.2 * -ode.gap[29] / kH).epsilon(1e-12));
  CHECK(oo.apexes.empty());
  CHECK(ode.gap[steps] < 0.0);
  CHECK(ode.gap[steps] > -1e-9);
  // A threshold above the impact speed: no restitution, the sphere stays in the floor (v >= 0).
  const BouncePath dead = bounce_path({.threshold = 5.0}, 1.0, 0.5, kG, kH, steps);
  CHECK(observe_bounce(dead.gap, dead.v, kG, kH).apexes.empty());
  CHECK(dead.v[28] == 0.0);
  // Energy never rises in the ideal law: each apex below the one before.
  const BouncePath half = bounce_path(kIdealBounce, 1.0, 0.5, kG, kH, 600);
  const auto oh = observe_bounce(half.gap, half.v, kG, kH, 3);
  REQUIRE(oh.apexes.size() == 3);
  CHECK(oh.apexes[0] < 1.0);
  CHECK(oh.apexes[1] < oh.apexes[0]);
  CHECK(oh.apexes[2] < oh.apexes[1]);
}

TEST_CASE(
    "bounce paths: a speculative contact turns the sphere before it touches; a split "
    "impulse pushes in position only",
    "[contact][reference]") {
  // Dropped 0.01 m inside a 0.02 m contact distance: step 1 (v = 0, nothing to restitute) lets
  // gravity act, step 2 allows closing the gap (target 0.5*g*h - gap/h < v_free), step 3 turns it:
  // v = e*2*g*h - gap/h, and the gap never closes.
  const BouncePath p = bounce_path({.contact_distance = 0.02}, 0.01, 0.5, kG, kH, 3);
  CHECK(p.v[1] == Approx(-kG * kH).epsilon(1e-14));
  CHECK(p.v[2] == Approx(-2 * kG * kH).epsilon(1e-14));
  CHECK(p.v[3] == Approx(0.5 * 2 * kG * kH - p.gap[2] / kH).epsilon(1e-12));
  CHECK(p.v[3] > 0.0);
  CHECK(p.gap[3] > 0.0);
  // The same drop with the distance given per size: 0.02 x a half diagonal of 1 m.
  const BouncePath q = bounce_path({.contact_distance_per_size = 0.02}, 0.01, 0.5, kG, kH, 3, 1.0);
  CHECK(q.gap == p.gap);
  // Split impulse after the 1 m fall: step 28 leaves at e*4.41 and moves 0.2*0.029 m more.
  const BouncePath s = bounce_path({.erp = 0.2, .push_in_position = true}, 1.0, 0.5, kG, kH, 28);
  CHECK(s.v[28] == Approx(2.205).epsilon(1e-12));
  CHECK(s.gap[28] == Approx(s.gap[27] + kH * 2.205 + 0.2 * -s.gap[27]).epsilon(1e-12));
}

TEST_CASE(
    "bounce paths: restitution of the post-gravity approach, a rebound threshold, a cap and a "
    "regularised row",
    "[contact][reference]") {
  // After the 1 m fall the impact step starts at -4.41 m/s; with the approach taken after its
  // gravity the rebound is e*(4.41 + g*h), and a row regularised by cfm stops 1/(1 + cfm) of the
  // way there from v_free = -(4.41 + g*h).
  const double in = 4.41 + kG * kH;
  const BouncePath after = bounce_path({.free_approach = true}, 1.0, 0.5, kG, kH, 28);
  CHECK(after.v[28] == Approx(0.5 * in).epsilon(1e-12));
  const double cfm = 1e-3;
  const BouncePath soft = bounce_path({.free_approach = true, .cfm = cfm}, 1.0, 0.5, kG, kH, 28);
  CHECK(soft.v[28] == Approx((cfm * -in + 0.5 * in) / (1.0 + cfm)).epsilon(1e-12));
  // A threshold of 0.5 m/s on the rebound stops e = 0.1's 0.457 m/s; on the approach it does not.
  const BouncePath on_rebound =
      bounce_path({.threshold = 0.5, .free_approach = true, .threshold_on_rebound = true}, 1.0, 0.1,
                  kG, kH, 28);
  const BouncePath on_approach =
      bounce_path({.threshold = 0.5, .free_approach = true}, 1.0, 0.1, kG, kH, 28);
  CHECK(on_rebound.v[28] == 0.0);
  CHECK(on_approach.v[28] == Approx(0.1 * in).epsilon(1e-12));
  // A cap of 1 m/s holds e = 0.5's rebound to it.
  const BouncePath capped = bounce_path({.max_rebound = 1.0}, 1.0, 0.5, kG, kH, 28);
  CHECK(capped.v[28] == 1.0);
}

TEST_CASE("a bounce turned by a speculative contact is observed at the step before the push",
          "[contact][reference]") {
  // Dropped 0.96 m with Bullet's members (r = 0.5 m: contact within 0.0173 m): step 26 ends
  // 0.0045 m above the floor at 4.2467 m/s, and step 27 leaves at e*4.2467 - 0.0045/h = 1.8533
  // m/s without the sphere ever entering the floor.
  const dropcheck::BounceLaw bullet{
      .erp = 0.2, .push_in_position = true, .threshold = 0.2, .contact_distance_per_size = 0.02};
  const BouncePath p = bounce_path(bullet, 0.96, 0.5, kG, kH, 60, 0.5 * std::sqrt(3.0));
  const auto o = observe_bounce(p.gap, p.v, kG, kH, 1);
  CHECK(o.contact_step == 26);
  CHECK(p.gap[26] > 0.0);
  CHECK(o.speed_in == Approx(26 * kG * kH).epsilon(1e-12));
  CHECK(o.speed_out == Approx(0.5 * 26 * kG * kH - p.gap[26] / kH).epsilon(1e-12));
  REQUIRE(o.apexes.size() == 1);
  CHECK(o.apexes[0] > 0.0);
}

TEST_CASE("a sphere on or under another body, or over a static sphere, is no floor bounce",
          "[contact][reference]") {
  using dropcheck::testing::body_text;
  const std::string ball = "shape = \"sphere\"\nradius = 0.5\n";
  const std::string bouncy = ball + "restitution = 0.5\n";
  const std::string text =
      dropcheck::testing::scene_head("1.0", "1/60", dropcheck::testing::kEarth,
                                     "contacts = true\n") +
      body_text("floor", "[0.0, -0.5, 0.0]", "",
                "static = true\nhalf_extents = [5.0, 0.5, 5.0]\n") +
      body_text("low", "[0.0, 1.5, 0.0]", "", bouncy) +
      body_text("high", "[0.0, 3.0, 0.0]", "", bouncy) +
      body_text("alone", "[3.0, 1.5, 0.0]", "", bouncy) +
      body_text("ball_floor", "[-3.0, 0.5, 0.0]", "", "static = true\n" + ball) +
      body_text("on_ball", "[-3.0, 2.0, 0.0]", "", bouncy);
  const dropcheck::Scene scene = dropcheck::parse_scene(text, "stack.toml");
  const auto setups = dropcheck::bounce_setups(scene);
  REQUIRE(setups.size() == 1);
  CHECK(scene.bodies[setups[0].body].name == "alone");
  // The landing oracle leaves out the same bodies, each with its reason.
  std::string reasons;
  for (const auto& e : dropcheck::landing_exclusions(scene)) reasons += e.sentence(scene) + "\n";
  CHECK_THAT(reasons, Catch::Contains("'on_ball' not judged: lands on static body 'ball_floor'") &&
                          Catch::Contains("'high' not judged: lands on dynamic body 'low'"));
}
