// Tests harness/oracles/landing.cpp against closed forms computed here: the parabola (k = 0), the
// damped fall of docs/engines.md section 1 (continuous model dv/dt = g - k*v), its a = 0 special
// case y(t) = y0 + v0*(1 - exp(-k*t))/k (solvable for t), and the discrete twin of every law at k =
// 0 (x_n = x0 - g*h^2*n*(n+1)/2, the same for all three orders when phi = 1).
#include "harness/oracles/landing.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "harness/scene/scene_loader.hpp"
#include "tests/shipped_scenes.hpp"

using namespace dropcheck;

namespace {

// Continuous model, docs/engines.md section 1, in long double: x(t) = x0 + (g/k)*t +
// (v0 - g/k)*(1 - exp(-k*t))/k.
double damped_fall(double x0, double v0, double g, double k, double t) {
  const long double gk = static_cast<long double>(g) / k;
  return static_cast<double>(x0 + gk * t +
                             (v0 - gk) * (1.0L - std::exp(-static_cast<long double>(k) * t)) / k);
}

// A one-body trajectory sampled every h with the given heights (velocity from differences).
Trajectory heights(double h, std::initializer_list<double> ys) {
  Trajectory t;
  t.h = h;
  t.body_names = {"cube"};
  double prev = *ys.begin();
  for (const double y : ys) {
    t.recorded.push_back(static_cast<std::int64_t>(t.recorded.size()));
    t.states.push_back({Vec3(0.0, y, 0.0), Vec3(0.0, (y - prev) / h, 0.0)});
    prev = y;
  }
  t.steps = t.recorded.back();
  return t;
}

// A unit cube on a floor whose top is at y = 0.
LandingSetup unit_cube_on_floor() {
  LandingSetup s;
  s.floor_top = 0.0;
  s.half_height = 0.5;
  s.rest_height = 0.5;
  return s;
}

const double kSeedK = -std::log(0.98) * 60.0;  // the seed's drag as a rate, 1.2121624 1/s

}  // namespace

TEST_CASE("The landing height is the parabola without damping and the damped closed form with it",
          "[landing]") {
  // y = y0 + v0*t + a*t^2/2: exact in double for these values (measured difference 0).
  CHECK(height_continuous(10.0, 2.0, -9.8, 0.0, 1.5) ==
        Approx(10.0 + 3.0 - 4.9 * 2.25).epsilon(0).margin(1e-14));
  for (const double t : {0.01, 0.5, 1.9, 10.0}) {
    INFO("t = " << t);
    // Against docs/engines.md's form in long double: measured <= 7.1e-15 m.
    CHECK(height_continuous(10.0, 1.0, -9.8, kSeedK, t) ==
          Approx(damped_fall(10.0, 1.0, -9.8, kSeedK, t)).epsilon(0).margin(1e-13));
    // Tiny k (the series branch, no cancellation): first order in k, y_k - y_0 =
    // -k*(v0*t^2/2 + a*t^3/6) (1.6e-9 m at t = 10 s for k = 1e-12); measured residual <= 7.4e-14 m
    // (t = 10 s).
    const double k = 1e-12;
    const double first_order = -k * (1.0 * t * t / 2 - 9.8 * t * t * t / 6);
    CHECK(height_continuous(10.0, 1.0, -9.8, k, t) - height_continuous(10.0, 1.0, -9.8, 0.0, t) ==
          Approx(first_order).epsilon(0).margin(2e-13));
  }
}

TEST_CASE("The landing contact time solves the undamped drop in closed form", "[landing]") {
  // Dropped from rest: 9.5 m = 9.8*t^2/2, t = sqrt(2*9.5/9.8) = 1.3923987... s.
  CHECK(contact_time_continuous(10.0, 0.0, -9.8, 0.0, 0.5) ==
        Approx(std::sqrt(19.0 / 9.8)).epsilon(1e-15));
  // Thrown up at 8 m/s from 1 m onto 0.5: t = (v0 + sqrt(v0^2 + 2*9.8*0.5))/9.8.
  CHECK(contact_time_continuous(1.0, 8.0, -9.8, 0.0, 0.5) ==
        Approx((8.0 + std::sqrt(64.0 + 9.8)) / 9.8).epsilon(1e-15));
  CHECK(contact_time_continuous(0.4, 0.0, -9.8, 0.0, 0.5) == 0.0);      // already down
  CHECK(std::isnan(contact_time_continuous(1.0, 1.0, 9.8, 0.0, 0.5)));  // pushed away
}

TEST_CASE("The landing contact time with damping is found to the last bits", "[landing]") {
  SECTION("no acceleration: y = y0 + v0*(1 - exp(-k*t))/k = target gives t = -ln(1 - k*d/|v0|)/k") {
    const double t = -std::log(1.0 - 1.2 * 1.0 / 3.0) / 1.2;
    // Measured relative difference 2.2e-16.
    CHECK(contact_time_continuous(1.0, -3.0, 0.0, 1.2, 0.0) == Approx(t).epsilon(1e-14));
    // Coasts at most |v0|/k = 2.5 m: never reaches 3 m below.
    CHECK(std::isnan(contact_time_continuous(3.0, -3.0, 0.0, 1.2, 0.0)));
  }
  SECTION("the seed's damped drop: y(t_c) is the target and just before it is above") {
    const double tc = contact_time_continuous(10.0, 0.0, -9.8, kSeedK, 0.5);
    CHECK(tc == Approx(1.91949942).epsilon(0).margin(1e-8));  // measured 1.919499421 s
    CHECK(damped_fall(10.0, 0.0, -9.8, kSeedK, tc) == Approx(0.5).epsilon(0).margin(1e-14));
    CHECK(height_continuous(10.0, 0.0, -9.8, kSeedK, tc * (1 - 1e-12)) > 0.5);
  }
  SECTION("pushed up while moving down: the first crossing, before the lowest point") {
    // a = +2, v0 = -5, k = 0.5: lowest at t = ln(1 + k*|v0|/a)/k = 1.622 s, y = -2.51 m.
    const double tc = contact_time_continuous(1.0, -5.0, 2.0, 0.5, 0.0);
    CHECK(tc < std::log(1.0 + 0.5 * 5.0 / 2.0) / 0.5);
    CHECK(height_continuous(1.0, -5.0, 2.0, 0.5, tc) == Approx(0.0).epsilon(0).margin(1e-14));
    CHECK(std::isnan(contact_time_continuous(10.0, -5.0, 2.0, 0.5, 0.0)));  // turns before
  }
}

TEST_CASE("landing_setups finds each dynamic body over a static floor box", "[landing]") {
  const Scene scene = testing::shipped("drop_on_floor");
  const std::vector<LandingSetup> drop = landing_setups(scene);
  REQUIRE(drop.size() == 1);
  CHECK(drop[0].body == 1);
  CHECK(drop[0].floor == 0);
  CHECK(drop[0].floor_top == 0.0);
  CHECK(drop[0].rest_height == 0.5);
  CHECK(drop[0].contact_time ==
        contact_time_continuous(10.0, 0.0, -9.8, scene.world.damping_rate, 0.5));

  // The seed's scene: both cubes are over the 10 m wide floor (top at 0).
  const std::vector<LandingSetup> seed = landing_setups(testing::shipped("seed_part3"));
  REQUIRE(seed.size() == 2);
  CHECK(seed[0].rest_height == 0.75);  // medium: half extent 0.75
  CHECK(seed[1].rest_height == 0.5);

  CHECK(landing_setups(testing::shipped("free_fall")).empty());  // no floor
  Scene beside = testing::shipped("drop_on_floor");
  beside.bodies[1].position.x() = 10.5;  // the floor reaches x = 10
  CHECK(landing_setups(beside).empty());
}

TEST_CASE("Every law's first landing contact is its discrete twin's, within two steps of t_c",
          "[landing][law]") {
  const Scene undamped = testing::shipped("drop_on_floor_undamped");
  const Scene damped = testing::shipped("drop_on_floor");
  const LandingSetup su = landing_setups(undamped).at(0), sd = landing_setups(damped).at(0);
  for (const DampingOrder law :
       {DampingOrder::AfterForces, DampingOrder::BeforeForces, DampingOrder::AfterPosition}) {
    for (const Timestep& h : undamped.timesteps) {
      INFO(to_string(law) << " at h = " << h.text);
      // k = 0, every order: x_n = 10 - 9.8*h^2*n*(n+1)/2 <= 0.5 first at the smallest n with
      // n*(n+1) >= 19/(9.8*h^2) (84 at 1/60).
      std::int64_t n = 0;
      while (10.0 - 9.8 * h.seconds * h.seconds * double(n * (n + 1)) / 2.0 > 0.5) ++n;
      CHECK(discrete_contact_step(law, undamped, h.seconds, su) == n);
      // Measured (t_law - t_c)/h from -1.17 (damping before forces, 1/60) to +0.83 (after
      // forces, 1/60) damped, -0.18 to +0.46 undamped: O(h) drift plus the sampling grid.
      const double t = double(discrete_contact_step(law, damped, h.seconds, sd)) * h.seconds;
      CHECK(std::abs(t - sd.contact_time) <= 2 * h.seconds);
    }
  }
}

TEST_CASE("observe_landing reads first contact, depth, rebound, rest offset and stillness",
          "[landing]") {
  const LandingSetup s = unit_cube_on_floor();
  SECTION("a landing that sinks, rebounds 2 cm and rests 0.1 mm deep for 2 s") {
    const Trajectory t =
        heights(0.5, {3.0, 2.0, 1.2, 0.4, 0.45, 0.52, 0.5, 0.5, 0.4999, 0.4999, 0.4999, 0.4999});
    const LandingObservation o = observe_landing(t, s);
    CHECK(o.first_contact_step == 3);
    CHECK(o.first_contact_time == 1.5);
    CHECK(o.deepest == Approx(-0.1).epsilon(0).margin(1e-15));
    CHECK(o.rebound == Approx(0.02).epsilon(0).margin(1e-15));
    CHECK(o.rest_offset == Approx(-1e-4).epsilon(0).margin(1e-15));
    CHECK(o.still_range ==
          Approx(1e-4).epsilon(0).margin(1e-15));  // window: steps 7 to 11 (last 2 s)
    CHECK(o.still);
  }
  SECTION("moving in the last 2 s is not still") {
    const Trajectory t = heights(0.5, {3.0, 1.2, 0.4, 0.5, 0.5, 0.5, 0.5, 0.51, 0.5});
    const LandingObservation o = observe_landing(t, s);
    CHECK(o.still_range == Approx(0.01).epsilon(0).margin(1e-15));
    CHECK_FALSE(o.still);
  }
  SECTION("a first contact inside the last 2 s is not still, however quiet") {
    const LandingObservation o = observe_landing(heights(0.5, {3.0, 2.0, 1.0, 0.5, 0.5}), s);
    CHECK(o.first_contact_step == 3);
    CHECK_FALSE(o.still);
  }
  SECTION("never down: no contact step, no rebound") {
    const LandingObservation o = observe_landing(heights(0.5, {3.0, 2.0, 1.0}), s);
    CHECK(o.first_contact_step == -1);
    CHECK(std::isnan(o.first_contact_time));
    CHECK(std::isnan(o.rebound));
    CHECK(o.rest_offset == 0.5);
    CHECK_FALSE(o.still);
  }
}

TEST_CASE("A stacked body is not judged by the landing oracle, and the reason names the other body",
          "[landing]") {
  const Scene stacks = testing::shipped("extreme/mass_ratio");
  const std::vector<LandingExclusion> out = landing_exclusions(stacks);
  REQUIRE(out.size() == 4);  // light_1e3, heavy_1e3, light_1e5, heavy_1e5: both stacks
  CHECK(out[0].sentence(stacks) ==
        "'light_1e3' not judged: dynamic body 'heavy_1e3' lands on it (the landing oracle covers "
        "one body over a static floor)");
  CHECK(out[1].sentence(stacks) ==
        "'heavy_1e3' not judged: lands on dynamic body 'light_1e3' (the landing oracle covers one "
        "body over a static floor)");
  CHECK(out[3].on_other);
  CHECK(stacks.bodies[out[3].other].name == "light_1e5");
  CHECK(engine_landing_setups(stacks, EngineInfo{}).empty());
  CHECK(landing_setups(stacks).size() == 4);  // the geometry still lists every fall

  // Side by side (footprints 0.1 m apart in x): two lone landings, both judged.
  Scene apart = stacks;
  apart.bodies[2].position.x() = -1.9;  // heavy_1e3 beside light_1e3 (half extents 0.5 each)
  const std::vector<LandingSetup> judged = engine_landing_setups(apart, EngineInfo{});
  REQUIRE(judged.size() == 2);
  CHECK(judged[0].body == 1);
  CHECK(judged[1].body == 2);

  // A lone drop is judged; the Box2D-style skin shift is applied to it alone.
  EngineInfo skin;
  skin.rest_offset = 0.015;
  skin.rest_tolerance = 1e-4;
  const std::vector<LandingSetup> drop =
      engine_landing_setups(testing::shipped("drop_on_floor"), skin);
  REQUIRE(drop.size() == 1);
  CHECK(drop[0].floor_top == Approx(0.0151).epsilon(0).margin(1e-15));
  CHECK(landing_exclusions(testing::shipped("drop_on_floor")).empty());
  // A slide or a bounce is judged by its own contact law, not as a landing: a cube sliding on at
  // the end of incline_slide is not "not still".
  CHECK(landing_setups(testing::shipped("incline_slide")).size() == 1);
  CHECK(engine_landing_setups(testing::shipped("incline_slide"), EngineInfo{}).empty());
  CHECK(engine_landing_setups(testing::shipped("bounce_e05"), EngineInfo{}).empty());
  CHECK(landing_setups(testing::shipped("slide_stop")).size() == 1);
  CHECK(engine_landing_setups(testing::shipped("slide_stop"), EngineInfo{}).empty());
}

TEST_CASE("Stillness is judged only over a window that lies wholly after first contact",
          "[landing]") {
  const LandingSetup s = unit_cube_on_floor();
  // Contact at step 3 (t = 1.5 s), run ends at step 4: 0.5 s after contact, window 2 s.
  const LandingObservation late = observe_landing(heights(0.5, {3.0, 2.0, 1.0, 0.5, 0.5}), s);
  CHECK_FALSE(late.still_judged);
  CHECK_FALSE(late.still);
  CHECK(late.after_contact == 0.5);
  // Contact at step 3, run ends at step 8: window = steps 4..8, after contact.
  const LandingObservation judged =
      observe_landing(heights(0.5, {3.0, 2.0, 1.0, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5}), s);
  CHECK(judged.still_judged);
  CHECK(judged.still);
  CHECK(judged.after_contact == 2.5);
  const LandingObservation never = observe_landing(heights(0.5, {3.0, 2.0, 1.0}), s);
  CHECK_FALSE(never.still_judged);
  CHECK(std::isnan(never.after_contact));
}

TEST_CASE("The law tunnels when no end-of-step position overlaps the floor slab", "[landing]") {
  const Scene thin = testing::shipped("extreme/thin_floor");
  const LandingSetup setup = landing_setups(thin).at(0);
  CHECK(setup.floor_bottom == Approx(-0.01).epsilon(0).margin(1e-15));
  // h = 1/60, after forces: v1 = -200 - 9.8/60, y1 = 2 + v1/60 = -1.33606 m, below the widened
  // slab [-0.51, 0.5] in one step of 3.33606 m (floor 0.01 m + height 1 m = 1.01 m).
  const Tunnelling t = discrete_tunnelling(DampingOrder::AfterForces, thin, 1.0 / 60.0, setup);
  CHECK(t.tunnels);
  CHECK(t.step == 1);
  CHECK(t.travel == Approx((200.0 + 9.8 / 60.0) / 60.0).epsilon(1e-12));
  CHECK(t.sentence() ==
        "tunnels: it travels 3.34 m per step at contact, more than the floor (0.01 m) plus its "
        "height (1 m)");
  // h = 1/1000: 0.2 m per step, the step ends inside the slab.
  const Tunnelling fine = discrete_tunnelling(DampingOrder::AfterForces, thin, 1e-3, setup);
  CHECK_FALSE(fine.tunnels);
  CHECK(fine.step >= 0);
  // A 10 m drop at 1/60 moves at most 0.23 m per step: it never jumps the 1 m floor.
  const Scene drop = testing::shipped("drop_on_floor");
  CHECK_FALSE(
      discrete_tunnelling(DampingOrder::AfterForces, drop, 1.0 / 60.0, landing_setups(drop).at(0))
          .tunnels);
}

TEST_CASE("Tunnelling is a limit without continuous collision and a fault with it", "[landing]") {
  const Scene thin = testing::shipped("extreme/thin_floor");
  const LandingSetup setup = landing_setups(thin).at(0);
  const Tunnelling law = discrete_tunnelling(DampingOrder::AfterForces, thin, 1.0 / 60.0, setup);
  // One-body runs (body 0) over the same floor.
  LandingSetup one = setup;
  one.body = 0;
  const Trajectory through = heights(1.0 / 60.0, {2.0, -1.3, -4.7});  // ends under the floor
  const Trajectory caught = heights(1.0 / 60.0, {2.0, 0.5, 0.5});
  EngineInfo plain, ccd;
  ccd.continuous_collision = true;
  CHECK(judge_tunnelling(law, plain, through, one) == TunnelVerdict::limit);
  CHECK(judge_tunnelling(law, ccd, through, one) == TunnelVerdict::fault);
  CHECK(judge_tunnelling(law, plain, caught, one) == TunnelVerdict::none);
  const Tunnelling fine = discrete_tunnelling(DampingOrder::AfterForces, thin, 1e-3, setup);
  CHECK(judge_tunnelling(fine, plain, through, one) == TunnelVerdict::none);  // judged as usual
}

TEST_CASE("A capped push-out's climb path: fall by the law, stop |v|*h deep, climb at the cap",
          "[landing]") {
  const Scene scene = testing::shipped("drop_on_floor_undamped");
  const LandingSetup setup = landing_setups(scene).at(0);
  const double h = scene.timestep.seconds, g = 9.8;
  EngineInfo info;  // semi-implicit Euler, damping after the forces (none here)
  info.law = Law{DampingOrder::AfterForces};
  CHECK_FALSE(climb_path(info, scene, h, setup).has_value());  // rigid: no climb path
  info.relative_cfm = {.cfm = 1e-5, .erp = 0.01, .max_push = 1e-3};
  const std::optional<ClimbPath> path = climb_path(info, scene, h, setup);
  REQUIRE(path.has_value());
  REQUIRE(path->y.size() == static_cast<std::size_t>(step_count(scene, h)) + 1);
  // The fall: y(n) = 10 - g*h^2*n*(n + 1)/2 to the first step at or below the rest height (84).
  const std::int64_t contact = discrete_contact_step(info.law, scene, h, setup);
  REQUIRE(contact == 84);
  for (const std::int64_t n : {std::int64_t{1}, contact})
    CHECK(path->y[n] == Approx(10.0 - g * h * h * double(n * (n + 1)) / 2.0).epsilon(1e-14));
  // Then every step climbs at the cap less cfm times the step's fall: the depth, 0.218 m, is far
  // above the cap's reach erp*d/h.
  const double climb = (1e-3 - 1e-5 * g * h * (double(contact) + 1.0)) / (1.0 + 1e-5);
  CHECK(path->y[contact + 1] - path->y[contact] == Approx(h * climb).epsilon(1e-9));
  CHECK(path->climb == Approx((1e-3 + 1e-5 * (path->climb - g * h)) / (1.0 + 1e-5)).epsilon(1e-9));
  // Without a cap there is no climb to follow: such a landing is judged by its rest offset.
  info.relative_cfm.max_push = std::numeric_limits<double>::infinity();
  CHECK_FALSE(climb_path(info, scene, h, setup).has_value());
}
