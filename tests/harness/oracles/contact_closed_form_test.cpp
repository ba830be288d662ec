// Tests harness/oracles/contact_closed_form.cpp: the continuous answer of the shipped contact
// scenes, against the closed forms each scene's description states.
#include "harness/oracles/contact_closed_form.hpp"

#include <catch2/catch.hpp>
#include <cmath>

#include "harness/oracles/analytic.hpp"
#include "tests/shipped_scenes.hpp"

using namespace dropcheck;

namespace {

constexpr double kClosedG = 9.8, kClosedH = 1.0 / 60.0;

// Body `name`'s state at step n of `t`.
const BodyState& at(const Trajectory& t, std::int64_t n, const std::string& name) {
  for (std::size_t i = 0; i < t.body_names.size(); ++i)
    if (t.body_names[i] == name) return t.at(static_cast<std::size_t>(n), i);
  FAIL("no body " << name);
  return t.at(0, 0);
}

}  // namespace

TEST_CASE("a slide's continuous answer: Coulomb's stop at v0^2/(2*mu*g) after v0/(mu*g)",
          "[contact][closed-form]") {
  const Trajectory t = *contact_closed_form(testing::shipped("slide_stop"), kClosedH);
  // 5 m/s on mu = 0.5: stops after 1.0204 s at 2.5510 m, then stays.
  const double reach = 25.0 / (2.0 * 0.5 * kClosedG);
  const BodyState& half = at(t, 30, "cube");
  CHECK(half.position.x() == Approx(5.0 * 0.5 - 0.25 * kClosedG * 0.25).epsilon(1e-14));
  CHECK(half.velocity.x() == Approx(5.0 - 0.5 * kClosedG * 0.5).epsilon(1e-14));
  CHECK(half.position.y() == 0.5);
  CHECK(at(t, 120, "cube").position.x() == Approx(reach).epsilon(1e-14));
  // Stopped after 5/(0.5*g) = 1.0204 s: moving at step 61 (1.0167 s), still from step 62.
  CHECK(at(t, 61, "cube").velocity.x() > 0.0);
  CHECK(at(t, 62, "cube").velocity.x() == 0.0);
  CHECK(at(t, 62, "cube").position.x() == Approx(reach).epsilon(1e-14));
  CHECK(at(t, 120, "cube").velocity.x() == 0.0);
}

TEST_CASE("a bounce's continuous answer: apexes e^(2n)*h0, at rest after t_fall*(1 + e)/(1 - e)",
          "[contact][closed-form]") {
  const Trajectory t = *contact_closed_form(testing::shipped("bounce_e05"), kClosedH);
  const double fall =
      std::sqrt(2.0 / kClosedG);  // h0 = 1 m, the sphere's centre 0.5 m above its bottom
  // The first apex, e*v_in/g after the impact: e^2*h0 = 0.25 m up.
  const double apex_time = fall + 0.5 * kClosedG * fall / kClosedG;
  std::int64_t n = 0;
  double highest = 0.0;
  for (std::int64_t k = 0; k <= t.steps; ++k) {
    const double y = at(t, k, "ball").position.y();
    if (static_cast<double>(k) * kClosedH > fall &&
        static_cast<double>(k) * kClosedH < 2.0 * apex_time - fall && y > highest) {
      highest = y;
      n = k;
    }
  }
  CHECK(std::abs(static_cast<double>(n) * kClosedH - apex_time) <= kClosedH);
  CHECK(highest <= 0.5 + 0.25 + 1e-12);
  CHECK(highest > 0.5 + 0.25 - 0.5 * kClosedG * kClosedH * kClosedH);
  // At rest after fall*(1 + e)/(1 - e) = 1.3553 s (every flight spent).
  CHECK(at(t, 90, "ball").position.y() == 0.5);
  CHECK(at(t, 90, "ball").velocity.y() == 0.0);
  CHECK(at(t, 80, "ball").position.y() > 0.5);  // 1.333 s: the last flights still go on
}

TEST_CASE("a landing's continuous answer: its free flight, then at rest on the floor",
          "[contact][closed-form]") {
  const Scene scene = testing::shipped("drop_on_floor");
  const Trajectory t = *contact_closed_form(scene, kClosedH);
  Scene free = scene;
  free.world.contacts = false;
  CHECK(at(t, 60, "cube").position == analytic_state(free, 1, 1.0).position);
  const BodyState& end = at(t, t.steps, "cube");
  CHECK(end.position.y() == 0.5);
  CHECK(end.velocity == Vec3::Zero());
}

TEST_CASE("a resting stack stays; a turning scene has no continuous contact answer",
          "[contact][closed-form]") {
  const Trajectory t = *contact_closed_form(testing::shipped("stack_rest"), kClosedH);
  CHECK(at(t, t.steps, "small").position.y() == 2.0);
  CHECK(at(t, t.steps, "medium").position.y() == 0.75);
  CHECK(contact_closed_form_unavailable(testing::shipped("tumble_drop")) == "a body turns");
  CHECK_FALSE(contact_closed_form(testing::shipped("tumble_drop"), kClosedH).has_value());
  // Every shipped planar contact scene has one.
  for (const char* name : {"slide_stop", "slide_diagonal", "incline_hold", "incline_slide",
                           "bounce_e01", "bounce_e09", "drop_on_floor_undamped"})
    CHECK(contact_closed_form_unavailable(testing::shipped(name)) == "");
}

TEST_CASE("a bounce's continuous answer in closed form: e = 1 keeps bouncing, e = 0 stops",
          "[contact][closed-form]") {
  Scene scene = testing::shipped("bounce_e05");
  for (Body& b : scene.bodies)
    if (b.restitution) b.restitution = 1.0;
  const Trajectory elastic = *contact_closed_form(scene, kClosedH);
  // Every flight returns to the drop height: 1 m above the floor, the centre at 1.5 m, after a
  // fall and a whole number of 2*sqrt(2/g) flights.
  const double fall = std::sqrt(2.0 / kClosedG);
  double highest_late = 0.0;
  for (std::int64_t n = 0; n <= elastic.steps; ++n)
    if (static_cast<double>(n) * kClosedH > fall)
      highest_late = std::max(highest_late, at(elastic, n, "ball").position.y());
  CHECK(highest_late <= 1.5 + 1e-12);
  CHECK(highest_late > 1.5 - 0.5 * kClosedG * kClosedH * kClosedH);
  for (Body& b : scene.bodies)
    if (b.restitution) b.restitution = 0.0;
  const Trajectory dead = *contact_closed_form(scene, kClosedH);
  CHECK(at(dead, dead.steps, "ball").position.y() == 0.5);
}

TEST_CASE("a box dropped onto another box, or landing with restitution, has no contact answer",
          "[contact][closed-form]") {
  Scene drop = testing::shipped("drop_on_floor");
  for (Body& b : drop.bodies)
    if (!b.is_static) b.restitution = 0.5;
  CHECK_THAT(contact_closed_form_unavailable(drop),
             Catch::Contains("lands with restitution outside a bounce setup"));
}

TEST_CASE("a slide keeps its answer in a scene with restitution: it never leaves its floor",
          "[contact][closed-form]") {
  Scene slide = testing::shipped("slide_stop");
  for (Body& b : slide.bodies)
    if (!b.is_static) b.restitution = 0.5;
  CHECK(contact_closed_form_unavailable(slide).empty());
}
