// Tests harness/study/stability_study.cpp: each engine is run at the scene's step and classified,
// measured against the closed form where there is one, given the theoretical edge of its own law
// (2/omega for semi-implicit Euler, 2*sqrt(2)/omega for RK4 on the drag-free spring) and searched
// from the scene's step; a slot without a factory comes back skipped, in its place.
#include "harness/study/stability_study.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "harness/core/registry.hpp"
#include "tests/faulty_engine.hpp"

using Catch::Matchers::Contains;
using namespace dropcheck;
using testing::extreme_scene;
using testing::registry_factory;

namespace {

struct Owned {
  std::unique_ptr<Engine> engine;
};

// ours-f64 declaring another law (its runs are ours-f64's; only the theory follows the law).
class StudyDeclares final : private Owned, public ForwardingEngine {
 public:
  explicit StudyDeclares(Law law)
      : Owned{make_engine("ours-f64")}, ForwardingEngine(*engine), law_(law) {}
  EngineInfo info() const override {
    EngineInfo i = inner_.info();
    i.name = "declares-rk4";
    i.law = law_;
    return i;
  }

 private:
  Law law_;
};

}  // namespace

TEST_CASE("the study runs each engine at the scene's step with the theory edge of its own law",
          "[stability][study]") {
  // stiff_spring: w = 60 rad/s, h = 1/32 (w*h = 1.875), 10 s.
  const Scene scene = extreme_scene("stiff_spring");
  const std::vector<EngineSlot> slots = {
      {"ours-f64", registry_factory("ours-f64"), ""},
      {"missing", EngineFactory(), "not compiled in"},
      {"declares-rk4", [] { return std::make_unique<StudyDeclares>(kRungeKutta4); }, ""}};
  StudyOptions options;
  options.search = false;
  std::ostringstream progress;
  const SceneStability s = study_scene(scene, slots, options, &progress);
  CHECK(s.name == "stiff_spring");
  CHECK(s.steps == 320);
  CHECK(s.no_analytic.empty());
  REQUIRE(s.engines.size() == 3);

  const EngineStability& ours = s.engines[0];
  CHECK(ours.label() == "ours-f64 (f64)");
  CHECK(ours.verdict.stable());
  CHECK(ours.steps_run == 320);
  CHECK(ours.theory_max_dt.value() == Approx(2.0 / 60.0).epsilon(1e-9));
  CHECK_FALSE(ours.search.has_value());
  // Against the closed form: semi-implicit Euler conserves w^2*x^2 + v^2 - h*w^2*x*v, so from rest
  // A = 0.0473 m off the equilibrium (which it shares with the physics) x swings at most
  // A/sqrt(1 - (w*h/2)^2) = 2.87*A: |dx| <= 3.87*A = 0.183 m. Its phase runs off by
  // w*T*(2*asin(w*h/2)/ (w*h) - 1) = 178 rad over the 10 s, so the error is of the order of the
  // amplitude, not small.
  REQUIRE(ours.vs_analytic.has_value());
  CHECK(ours.vs_analytic->max_dx > 0.01);
  CHECK(ours.vs_analytic->max_dx <= 0.184);

  CHECK_FALSE(s.engines[1].ran());
  CHECK(s.engines[1].skipped == "not compiled in");
  // RK4's edge on the imaginary axis: w*h = 2*sqrt(2).
  CHECK(s.engines[2].engine == "declares-rk4");
  CHECK(s.engines[2].theory_max_dt.value() == Approx(2.0 * std::sqrt(2.0) / 60.0).epsilon(1e-9));
  CHECK(progress.str() ==
        "stability stiff_spring: ours-f64 (f64) stable\n"
        "stability stiff_spring: missing skipped (not compiled in)\n"
        "stability stiff_spring: declares-rk4 (f64) stable\n");
}

TEST_CASE("the study searches from the scene's step: beyond the edge it finds 2/omega below",
          "[stability][study]") {
  Scene scene = extreme_scene("stiff_spring");
  scene.timestep = {1.0 / 29.0, "1/29"};  // w*h = 2.069: unstable
  scene.duration = 2.0;
  std::ostringstream progress;
  const SceneStability s =
      study_scene(scene, {{"ours-f64", registry_factory("ours-f64"), ""}}, {}, &progress);
  REQUIRE(s.engines.size() == 1);
  const EngineStability& e = s.engines[0];
  REQUIRE_FALSE(e.verdict.stable());
  CHECK(e.verdict.failures.front().mode == FailureMode::unbounded_growth);
  REQUIRE(e.search.has_value());
  CHECK(e.search->start == 1.0 / 29.0);
  CHECK(e.search->max_stable_dt <= 2.0 / 60.0);
  CHECK(e.search->max_stable_dt > 0.99 * 2.0 / 60.0);
  CHECK(e.search->min_unstable_dt >= 2.0 / 60.0);
  CHECK_THAT(progress.str(), Contains("stability stiff_spring: ours-f64 (f64) unbounded growth, " +
                                      std::to_string(e.search->probes) + " probes\n"));
}

TEST_CASE("a contact scene has no closed form to measure against", "[stability][study]") {
  const Scene scene = extreme_scene("thin_floor");
  StudyOptions options;
  options.search = false;
  const SceneStability s = study_scene(scene,
                                       {{"faulty",
                                         [] {
                                           return std::make_unique<testing::FaultyEngine>(
                                               testing::FaultyEngine::Fault::none, 0);
                                         },
                                         ""}},
                                       options);
  CHECK_FALSE(s.no_analytic.empty());
  REQUIRE(s.engines.size() == 1);
  CHECK_FALSE(s.engines[0].vs_analytic.has_value());
  CHECK_FALSE(s.engines[0].theory_max_dt.has_value());  // free flight: no step bound
  REQUIRE_FALSE(s.engines[0].verdict.stable());
  CHECK(s.engines[0].verdict.failures.front().mode == FailureMode::tunnelled);
}
