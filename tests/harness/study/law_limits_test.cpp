// Tests the causes a check names (harness/study/checks.cpp, law_stability.cpp, sweep.cpp): an
// engine that blows up where its own law is unstable is a LIMIT, in its own arithmetic or another;
// blowing up where the law is stable, or leaving the law first, still fails; a pre-asymptotic sweep
// is extended until its order is in band, and a sweep that never gets there still fails.
#include <catch2/catch.hpp>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/registry.hpp"
#include "harness/judge/law_stability.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/checks.hpp"
#include "harness/study/sweep.hpp"
#include "tests/engine_slots.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;

namespace {

// ours-f64 behind another declaration: arithmetic not copied (as ODE and MuJoCo), and, like
// MuJoCo, an engine error once a coordinate exceeds `huge` or from step `fail_at` on.
class GuardedEngine final : public Engine {
 public:
  GuardedEngine(double huge, long fail_at, Law law)
      : huge_(huge), fail_at_(fail_at), law_(law), inner_(make_engine("ours-f64")) {}

  EngineInfo info() const override {
    EngineInfo i = inner_->info();
    i.name = "guarded";
    i.arithmetic = DampingForm::other;
    i.law = law_;
    return i;
  }
  void load(const Scene& scene, double h) override {
    inner_->load(scene, h);
    steps_ = 0;
    states_.assign(scene.bodies.size(), {});
  }
  void set_forces(std::span<const Vec3> f) override { inner_->set_forces(f); }
  void step() override {
    inner_->step();
    inner_->read(states_);
    if (++steps_ >= fail_at_ || states_[0].position.cwiseAbs().maxCoeff() > huge_)
      throw EngineError("huge value at step " + std::to_string(steps_));
  }
  void read(std::span<BodyState> out) const override { inner_->read(out); }

 private:
  double huge_;
  long fail_at_, steps_ = 0;
  std::vector<BodyState> states_;
  Law law_;
  std::unique_ptr<Engine> inner_;
};

EngineFactory guarded(double huge, long fail_at, Law law = DampingOrder::AfterForces) {
  return [=] { return std::make_unique<GuardedEngine>(huge, fail_at, law); };
}
const Timestep kUnstable{1.0 / 25, "1/25"};  // omega*h = 2.4 on stiff_spring: beyond 2

// extend_sweep on heavy_drag from h = 1/30 and 1/60, every error, observed or added, from `error`.
ExtendedSweep sweep_of(double (*error)(double h)) {
  const Scene scene = load_scene("scenarios/extreme/heavy_drag.toml");
  std::vector<double> h{1.0 / 30, 1.0 / 60}, e{error(h[0]), error(h[1])};
  return extend_sweep(scene, h, e, 0.0,
                      [&](double s, std::string&) { return std::optional<double>(error(s)); });
}

}  // namespace

TEST_CASE("ours blowing up where its own law is unstable is a LIMIT naming omega*h and the edge",
          "[checks][limits]") {
  const Scene scene = load_scene("scenarios/extreme/stiff_spring.toml");
  const CheckResult r = check_own_law(scene, testing::factory("ours"), kUnstable);
  INFO(r.limit << " | " << r.message);
  CHECK(r.passed);
  CHECK_THAT(r.limit, Contains("unstable at h = 1/25: omega*h = 2.4 > 2") &&
                          Contains("semi-implicit Euler") && Contains("'bob'"));
  CHECK_THAT(r.message, Contains("NaN/Inf") && Contains("it follows its law"));
}

TEST_CASE(
    "an engine in another arithmetic stopping with an error where its law is unstable is a "
    "LIMIT",
    "[checks][limits]") {
  const Scene scene = load_scene("scenarios/extreme/stiff_spring.toml");
  const CheckResult r = check_own_law(scene, guarded(1e10, 1L << 40), kUnstable);
  INFO(r.limit << " | " << r.message);
  CHECK(r.passed);
  CHECK_THAT(r.limit, Contains("omega*h = 2.4 > 2"));
  CHECK_THAT(r.message, Contains("huge value") && Contains("order not copied"));
}

TEST_CASE(
    "an engine blowing up where its law is stable, or leaving its law where the law is unstable, "
    "still fails with no limit",
    "[checks][limits]") {
  // The second row's premise: Bullet's order is unstable at 1/25 on stiff_spring_drag.
  REQUIRE_FALSE(law_instability(load_scene("scenarios/extreme/stiff_spring_drag.toml"),
                                DampingOrder::BeforeForces, kUnstable)
                    .empty());
  // Each row: what it is, its scene, the engine, the step (none: the scene's own) and the message.
  struct Case {
    std::string what, scene;
    EngineFactory engine;
    std::optional<Timestep> h;
    std::vector<std::string> says;
  };
  const std::vector<Case> cases{
      {"blowing up where its law is stable (omega*h 1.875 at the scene's step)",
       "stiff_spring",
       guarded(1e10, 50),
       std::nullopt,
       {"run failed", "huge value at step 50"}},
      // Runs ours' order (stable at 1/25 here) while declaring Bullet's (unstable): it stays finite
      // while its declared law grows, so it departs from that law long before the law overflows.
      {"leaving its declared law where that law is unstable",
       "stiff_spring_drag",
       guarded(1e10, 1L << 40, DampingOrder::BeforeForces),
       kUnstable,
       {"it departs from its law", "worst at body 'bob'"}},
  };
  for (const Case& c : cases) {
    const Scene scene = load_scene("scenarios/extreme/" + c.scene + ".toml");
    const CheckResult r = check_own_law(scene, c.engine, c.h.value_or(scene.timestep));
    INFO(c.what << ": " << r.message);
    CHECK_FALSE(r.passed);
    CHECK(r.limit.empty());
    for (const std::string& text : c.says) CHECK_THAT(r.message, Contains(text));
  }
}

TEST_CASE("a law is stable below its edge and unstable above it, with drag moving the edge",
          "[checks][limits]") {
  const Scene spring = load_scene("scenarios/extreme/stiff_spring.toml");
  CHECK(law_instability(spring, DampingOrder::AfterForces, {1.0 / 32, "1/32"}).empty());
  CHECK_THAT(law_instability(spring, DampingOrder::AfterForces, {1.0 / 29, "1/29"}),
             Contains("omega*h = 2.069 > 2"));
  const Scene drag = load_scene("scenarios/extreme/stiff_spring_drag.toml");
  // Edges 0.041 s (after the forces) and 0.028 s (Bullet's order) on this scene.
  CHECK(law_instability(drag, DampingOrder::AfterForces, {1.0 / 25, "1/25"}).empty());
  CHECK_THAT(law_instability(drag, DampingOrder::BeforeForces, {1.0 / 30, "1/30"}),
             Contains("> 1.676") && Contains("world damping k = 20 1/s"));
  CHECK(law_instability(load_scene("scenarios/free_fall_drag.toml"), DampingOrder::BeforeForces,
                        {1.0, "1"})
            .empty());
}

TEST_CASE("a pre-asymptotic sweep is extended until its order is in band, and names k*h",
          "[checks][limits]") {
  const Scene scene = load_scene("scenarios/extreme/heavy_drag.toml");
  const CheckResult r =
      check_divergence(scene, testing::factory("ours-f64"), testing::factory("ours-f64"));
  INFO(r.message);
  CHECK(r.passed);
  CHECK(r.limit.empty());
  CHECK_THAT(r.message,
             Contains("pre-asymptotic (k*h = 0.5 at the sweep's finest step h = 1/120") &&
                 Contains("extended by 1 halving") && Contains("0.937"));
}

TEST_CASE("the divergence leaves out the steps where a law is unstable and says so",
          "[checks][limits]") {
  if (!make_engine("bullet")) return;  // Bullet not compiled in
  const Scene scene = load_scene("scenarios/extreme/stiff_spring_drag.toml");
  const CheckResult r =
      check_divergence(scene, testing::factory("bullet"), testing::factory("ours-f64"));
  INFO(r.message);
  CHECK(r.passed);
  CHECK_THAT(r.message, Contains("left out of the order: h = 1/25, 1/30 (bullet: its law"));
}

TEST_CASE("a sweep that extends into the first-order band is reached", "[sweep][limits]") {
  // h^2 dominates at first.
  const ExtendedSweep x = sweep_of([](double h) { return 5.0 * h + 400.0 * h * h; });
  CHECK(x.reached);
  CHECK(x.added >= 2);
  CHECK(x.stopped.empty());
}

TEST_CASE("an inconsistent law whose error never shrinks at first order still fails",
          "[sweep][limits]") {
  // Converges to 0.3 m, not to the model.
  const ExtendedSweep x = sweep_of([](double h) { return 0.3 + h; });
  CHECK_FALSE(x.reached);
  CHECK_THAT(x.stopped, Contains("cost cap"));
  CHECK(x.estimate.orders.back() < 0.1);
}

TEST_CASE("a reference that departs from its own law is not extended", "[checks][limits]") {
  // A guarded engine declaring Bullet's order while running ours', as its own reference.
  const Scene scene = load_scene("scenarios/extreme/heavy_drag.toml");
  const EngineFactory wrong = guarded(1e300, 1L << 40, DampingOrder::BeforeForces);
  const CheckResult r = check_divergence(scene, wrong, wrong);
  INFO(r.message);
  CHECK_FALSE(r.passed);
  CHECK_THAT(r.message, Contains("not extended: guarded departs from its own law"));
}
