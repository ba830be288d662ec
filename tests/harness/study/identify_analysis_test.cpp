// Tests harness/study/identify_analysis.cpp: what `dropcheck identify` measures and concludes, read
// from its structs (the printed lines are tested in tests/harness/cli/run_test.cpp).
#include "harness/study/identify_analysis.hpp"

#include <catch2/catch.hpp>

#include "harness/core/registry.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"

using namespace dropcheck;

namespace {

// The engine `name` for every scene, mapped as `dropcheck check` maps it, at the scene's step.
IdentifySource source(const std::string& name) {
  return {[name]() -> std::optional<EngineInfo> { return make_engine(name)->info(); },
          [name](const Scene&) {
            return FrictionEngine{make_engine(name), false};
          },
          [](const Scene& s) { return s.timestep.seconds; }};
}

}  // namespace

TEST_CASE("identify on an engine: its law named, as declared, and its order measured",
          "[identify][analysis]") {
  const Scene scene = load_scene("scenarios/wind.toml");
  const std::unique_ptr<Engine> engine = make_engine("ours-f64");
  const EngineIdentity e = identify_engine(scene, *engine, scene.timestep.seconds);
  CHECK(e.scene == "wind");
  CHECK(e.info.name == "ours-f64");
  CHECK_FALSE(e.accuracy.has_value());
  CHECK_FALSE(e.failed.has_value());
  REQUIRE(e.fit.has_value());
  const FreeFlightIdentity& f = *e.fit;
  CHECK(f.engine == "ours-f64");
  CHECK(f.h == scene.timestep.seconds);
  CHECK(f.named());
  CHECK(f.law.fits[f.law.best].law == Law{DampingOrder::AfterForces});
  CHECK(f.declared == Law{DampingOrder::AfterForces});
  CHECK(f.law_match == DeclaredMatch::matches);
  REQUIRE(f.order.has_value());
  CHECK(f.order->unavailable.empty());
  CHECK(f.order->h.size() >= 2);
  CHECK(f.order_matches);
  CHECK_FALSE(f.rotation.has_value());
  CHECK_FALSE(f.rotation_unread);
  CHECK(f.ok());
  CHECK(e.ok());
}

TEST_CASE("identify on a trajectory alone: the law named, nothing declared",
          "[identify][analysis]") {
  const Scene scene = load_scene("scenarios/wind.toml");
  const std::unique_ptr<Engine> engine = make_engine("ours");
  const Trajectory run = run_scene(*engine, scene, scene.timestep.seconds);
  const FreeFlightIdentity f = identify_free_flight(scene, run);
  CHECK(f.engine == "ours");
  CHECK(f.bodies == run.bodies());
  CHECK(f.steps == run.steps);
  CHECK(f.named());
  CHECK(f.law.fits[f.law.best].law == Law{DampingOrder::AfterForces});
  CHECK_FALSE(f.declared.has_value());
  CHECK_FALSE(f.order.has_value());
  CHECK(f.ok());
}

TEST_CASE("identify on a gravity-only scene: two members tie, the declared one among them",
          "[identify][analysis]") {
  const Scene scene = load_scene("scenarios/free_fall_drag.toml");
  const std::unique_ptr<Engine> engine = make_engine("ours-f64");
  const EngineIdentity e = identify_engine(scene, *engine, scene.timestep.seconds);
  REQUIRE(e.fit.has_value());
  CHECK(e.fit->law.ambiguous);
  CHECK_FALSE(e.fit->named());
  CHECK(e.fit->law_match == DeclaredMatch::tied);
  CHECK_FALSE(e.ok());
}

TEST_CASE("identify on a turning engine: its rotational member against the declared one",
          "[identify][analysis][rotation]") {
  if (!make_engine("mujoco")) return;  // MuJoCo not compiled in
  const Scene scene = load_scene("scenarios/gazebo_boxes_complex.toml");
  const std::unique_ptr<Engine> engine = make_engine("mujoco");
  const EngineIdentity e = identify_engine(scene, *engine, scene.timestep.seconds);
  REQUIRE(e.fit.has_value());
  REQUIRE(e.fit->rotation.has_value());
  CHECK(e.fit->rotation_named());
  REQUIRE(e.fit->rotation_declared.has_value());
  CHECK(e.fit->rotation_declared->member.law == e.info.rotation_law);
  CHECK(e.fit->rotation_declared->match == DeclaredMatch::matches);
}

TEST_CASE("identify on an error-controlled engine: its error per accuracy, no fit",
          "[identify][analysis][error-controlled]") {
  if (!make_engine("simbody-rkm")) return;  // Simbody not compiled in
  const Scene scene = load_scene("scenarios/free_fall_drag.toml");
  const std::unique_ptr<Engine> engine = make_engine("simbody-rkm");
  const EngineIdentity e = identify_engine(scene, *engine, scene.timestep.seconds);
  REQUIRE(e.accuracy.has_value());
  CHECK(e.accuracy->points.size() == std::size(kAccuraciesMeasured));
  CHECK(e.accuracy->within());
  CHECK_FALSE(e.fit.has_value());
  CHECK(e.ok());
}

TEST_CASE("identify on a slide: both stop distances, the model named and declared",
          "[identify][analysis][contact]") {
  if (!make_engine("ode")) return;  // ODE not compiled in
  const Scene scene = load_scene("scenarios/slide_stop.toml");
  const FrictionModelIdentity f = identify_friction_model(scene, source("ode"));
  CHECK(f.scene == "slide_stop");
  CHECK(f.engine == "ode");
  CHECK_FALSE(f.planar);
  CHECK_FALSE(f.failed.has_value());
  CHECK(f.still_sliding_angle == -1);
  CHECK_FALSE(f.raw);
  REQUIRE(f.found.has_value());
  CHECK(f.found->ratio == Approx(0.70229).epsilon(1e-4));
  CHECK(f.found->named == FrictionModel::box_pyramid);
  CHECK(f.declared == FrictionModel::box_pyramid);
  CHECK(f.ok());
}

TEST_CASE("identify on a ramp names each engine's declared model",
          "[identify][analysis][contact]") {
  // Measured ratios at 45 over 0 degrees on incline_slide: ODE 0.00021 and DART 1.2e-6 (box
  // pyramid: held at 45 degrees but for a creep), MuJoCo 2.896 (sum pyramid, 2.8933), Bullet 1.0092
  // and ours 1 (cone). On incline_hold only the sum pyramid slips at 45 degrees (MuJoCo 0.446 m).
  const Scene ramp = load_scene("scenarios/incline_slide.toml");
  const Scene hold = load_scene("scenarios/incline_hold.toml");
  for (const char* name : {"ode", "bullet", "mujoco", "dart", "ours"}) {
    if (!make_engine(name)) continue;  // not compiled in
    const FrictionModelIdentity f = identify_friction_model(ramp, source(name));
    REQUIRE(f.found.has_value());
    INFO(name << ": " << f.found->sentence());
    CHECK(f.found->named == f.declared);
    CHECK(f.ok());
    const FrictionModelIdentity g = identify_friction_model(hold, source(name));
    REQUIRE(g.found.has_value());
    INFO(g.found->sentence());
    CHECK(g.ok());
    CHECK(g.found->named.has_value() == (g.declared == FrictionModel::sum_pyramid));
  }
}

TEST_CASE("identify on a slide with a 2-D engine: not applicable, nothing run",
          "[identify][analysis][contact]") {
  if (!make_engine("box2d")) return;  // Box2D not compiled in
  const Scene scene = load_scene("scenarios/slide_stop.toml");
  const FrictionModelIdentity f = identify_friction_model(scene, source("box2d"));
  CHECK(f.planar);
  CHECK(f.engine == "box2d");
  CHECK_FALSE(f.found.has_value());
  CHECK(f.ok());
}

TEST_CASE("identify --combine: the pair's coefficient and the rule it names",
          "[identify][analysis][contact]") {
  const Scene scene = load_scene("scenarios/slide_stop.toml");
  if (const std::unique_ptr<Engine> bullet = make_engine("bullet")) {
    const CombineRuleIdentity c = identify_combine_rule(scene, *bullet, source("bullet"));
    CHECK(c.engine == "bullet");
    CHECK_FALSE(c.per_pair);
    REQUIRE(c.found.has_value());
    CHECK(c.found->mu_seen == Approx(0.16).epsilon(1e-3));
    CHECK(c.found->named == "product");
    CHECK(c.ok());
  }
  if (const std::unique_ptr<Engine> ode = make_engine("ode")) {
    const CombineRuleIdentity c = identify_combine_rule(scene, *ode, source("ode"));
    CHECK(c.per_pair);
    CHECK_FALSE(c.found.has_value());
    CHECK(c.ok());
  }
}
