// Tests harness/study/divergence.cpp: what the cross-engine check measures over a sweep, read from
// its struct (the check's message is tested in checks_test.cpp and law_limits_test.cpp).
#include "harness/study/divergence.hpp"

#include <catch2/catch.hpp>

#include "harness/core/registry.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/engine_slots.hpp"

using namespace dropcheck;

TEST_CASE("the reference's convergence: every step against the closed form and its own law",
          "[divergence]") {
  const Scene scene = load_scene("scenarios/free_fall_drag.toml");
  const Divergence d =
      measure_divergence(scene, testing::factory("ours-f64"), testing::factory("ours-f64"));
  CHECK(d.engine == "ours-f64");
  CHECK(d.reference == "ours-f64");
  CHECK(d.to_analytic);
  REQUIRE(d.steps.size() == 4);  // 1/30, 1/60, 1/120, 1/240
  for (const DivergenceStep& s : d.steps) {
    INFO("h = " << s.h.text);
    CHECK(s.measured());
    REQUIRE(s.own.has_value());
    CHECK(s.own->follows());
    CHECK(s.own_tolerance > 0.0);
    CHECK_FALSE(s.attribution.has_value());
    CHECK(s.error > 0.0);
  }
  // First order: the error halves with h.
  CHECK(d.steps[0].error / d.steps[1].error == Approx(2.0).epsilon(0.1));
  REQUIRE(d.measured_h().size() == 4);
  CHECK(d.measured_h()[0] == Approx(1.0 / 30));
  CHECK(d.measured_errors()[3] == d.steps[3].error);
  CHECK(d.finding == DivergenceFinding::order);
  REQUIRE(d.order.has_value());
  CHECK(d.order->first_order);
  CHECK(d.order->measurable);
  CHECK(d.noise > 0.0);
  CHECK(d.passed);
  CHECK_FALSE(d.limit());
  CHECK_FALSE(d.extended.has_value());
  CHECK(d.first_left_out() == nullptr);
  CHECK(d.first_departure() == nullptr);
}

TEST_CASE("two engines with one law: every step explained, the law part within rounding",
          "[divergence]") {
  const Scene scene = load_scene("scenarios/free_fall_drag.toml");
  const Divergence d =
      measure_divergence(scene, testing::factory("ours"), testing::factory("ours-f64"));
  CHECK(d.engine == "ours");
  CHECK(d.reference == "ours-f64");
  CHECK_FALSE(d.to_analytic);
  REQUIRE(d.steps.size() == 4);
  for (const DivergenceStep& s : d.steps) {
    REQUIRE(s.attribution.has_value());
    CHECK(s.attribution->explained());
    CHECK(s.attribution->law_difference.empty());
    CHECK(s.attribution->total > 0.0);  // float against double
    CHECK(s.error == 0.0);
    CHECK_FALSE(s.own.has_value());
  }
  CHECK(d.finding == DivergenceFinding::same_law);
  CHECK(d.passed);
  CHECK(d.rotations_apart() == nullptr);
  CHECK_FALSE(d.order.has_value());
}

TEST_CASE("two laws that differ in the damping order: the law part, shrinking at first order",
          "[divergence]") {
  if (!make_engine("bullet")) return;  // Bullet not compiled in
  const Scene scene = load_scene("scenarios/free_fall_drag.toml");
  const Divergence d =
      measure_divergence(scene, testing::factory("bullet"), testing::factory("ours-f64"));
  REQUIRE(d.steps.size() == 4);
  for (const DivergenceStep& s : d.steps) {
    REQUIRE(s.attribution.has_value());
    CHECK(s.attribution->explained());
    CHECK(s.attribution->law_difference == "damping-order");
    CHECK(s.error == s.attribution->law_part);
    CHECK(s.error > 0.0);
  }
  CHECK(d.finding == DivergenceFinding::order);
  CHECK(d.order->first_order);
  CHECK(d.passed);
}

TEST_CASE("a scene the reference has no closed form for is not run", "[divergence]") {
  const Scene scene = load_scene("scenarios/spin_drag.toml");
  const Divergence d =
      measure_divergence(scene, testing::factory("ours-f64"), testing::factory("ours-f64"));
  CHECK(d.finding == DivergenceFinding::no_closed_form);
  CHECK_FALSE(d.no_closed_form.empty());
  CHECK(d.steps.empty());
  CHECK(d.passed);
}

TEST_CASE("the steps where a law is unstable are left out, with whose law it is",
          "[divergence][limits]") {
  if (!make_engine("bullet")) return;  // Bullet not compiled in
  const Scene scene = load_scene("scenarios/extreme/stiff_spring_drag.toml");
  const Divergence d =
      measure_divergence(scene, testing::factory("bullet"), testing::factory("ours-f64"));
  const DivergenceStep* first = d.first_left_out();
  REQUIRE(first != nullptr);
  CHECK(first->h.text == "1/25");
  CHECK(first->unstable_engine == "bullet");
  CHECK_FALSE(first->unstable.empty());
  CHECK_FALSE(first->measured());
  CHECK_FALSE(first->attribution.has_value());
  CHECK(d.measured_h().size() + 2 == d.steps.size());  // 1/25 and 1/30 left out
  CHECK(d.passed);
}

TEST_CASE("a pre-asymptotic sweep is extended, and the struct holds why and how far",
          "[divergence][limits]") {
  const Scene scene = load_scene("scenarios/extreme/heavy_drag.toml");
  const Divergence d =
      measure_divergence(scene, testing::factory("ours-f64"), testing::factory("ours-f64"));
  CHECK(d.finding == DivergenceFinding::extended);
  REQUIRE(d.order.has_value());
  CHECK_FALSE(d.order->first_order);
  CHECK(d.order->measurable);
  CHECK(d.pre_asymptotic.find("k*h = 0.5") != std::string::npos);
  REQUIRE(d.extended.has_value());
  CHECK(d.extended->reached);
  CHECK(d.extended->added == 1);
  CHECK(d.extended->h.size() == d.measured_h().size() + 1);
  CHECK(d.passed);
  CHECK_FALSE(d.drift.has_value());
  CHECK_FALSE(d.limit());
}
