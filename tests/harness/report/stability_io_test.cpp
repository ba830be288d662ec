// Tests harness/report/stability_io.cpp: the JSON and text forms of a stability study carry the
// verdicts, the search's result and the skipped engines; the JSON parses, keeps every digit and
// writes null for what is absent or not finite; the search's one-line summary in each shape.
#include "harness/report/stability_io.hpp"

#include <catch2/catch.hpp>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/registry.hpp"
#include "harness/io/json_text.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/stability_study.hpp"
#include "tests/engine_slots.hpp"
#include "tests/shipped_scenes.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::EndsWith;
using Catch::Matchers::StartsWith;
using namespace dropcheck;

using dropcheck::testing::slots;

TEST_CASE("Stability: the study's JSON and text carry verdicts, the search and skipped engines",
          "[stability][report]") {
  const Scene scene = load_scene(kTinyStepScene);
  const SceneStability s = study_scene(scene, slots({"ours", "ours-f64"}));
  const std::string json = stability_to_json(s, StudyOptions{}.search_options);
  CHECK_THAT(json, Contains("\"engine\":\"ours\",\"scalar\":\"f32\"") &&
                       Contains("\"verdict\":\"frozen\""));
  CHECK_THAT(json, Contains("\"min_stable_dt\":") && Contains("\"max_stable_dt\":"));
  const std::string text = stability_to_text(s);
  CHECK_THAT(text, Contains("ours (f32)       frozen") && Contains("frozen below"));
  const SceneStability floor =
      study_scene(load_scene(DROPCHECK_SOURCE_DIR "/scenarios/extreme/thin_floor.toml"),
                  slots({"wildmagic"}), StudyOptions{});
  // An engine without contacts (Wild Magic: free flight only) is listed with the reason it did not
  // run, or why it is not in this build.
  const std::string absent = engine_unavailable_reason("wildmagic");
  const std::string why = absent.empty() ? "no contacts" : absent;
  REQUIRE(floor.engines.size() == 1);
  CHECK(floor.engines.front().skipped == why);
  CHECK_THAT(stability_to_json(floor, {}),
             Contains("{\"engine\":\"wildmagic\",\"skipped\":\"" + why + "\"}"));
}

namespace {

StepSearch searched(double max_stable, double min_unstable, std::optional<FailureMode> limit) {
  StepSearch s;
  s.max_stable_dt = max_stable;
  s.min_unstable_dt = min_unstable;
  s.limit = limit;
  s.start = 0.1;
  s.cap = 0.25;
  s.horizon = 10.0;
  s.probes = 7;
  return s;
}

}  // namespace

TEST_CASE("search_summary says where the search stopped, in each of its shapes",
          "[stability][report]") {
  const double nan = StepSearch::none;
  CHECK(search_summary(searched(0.033303, 0.0333481, FailureMode::unbounded_growth)) ==
        "fails at 0.0333481 s (unbounded growth)");
  CHECK(search_summary(searched(0.25, nan, std::nullopt)) == "no failure up to the cap 0.25 s");
  CHECK(search_summary(searched(nan, 0.0001, FailureMode::non_finite)) ==
        "NaN/Inf at every h tried, from 0.1 s down to 0.0001 s");
  StepSearch frozen = searched(0.2, 0.21, FailureMode::engine_error);
  frozen.min_stable_dt = 8e-5;
  CHECK(search_summary(frozen) == "frozen below 8e-05 s; fails at 0.21 s (engine error)");
  StepSearch always = searched(nan, nan, FailureMode::frozen);
  always.start = 1e-5;
  CHECK(search_summary(always) == "frozen at every h tried, from 1e-05 s up to the cap 0.25 s");
}

TEST_CASE("the study's JSON is valid, exact, and null where a value is absent or not finite",
          "[stability][report]") {
  SceneStability s;
  s.name = "spring";
  s.source = "spring.toml";
  s.h = {1.0 / 30.0, "1/30"};
  s.duration = 10.0;
  s.steps = 300;
  EngineStability ran;
  ran.engine = "ours";
  ran.scalar = Scalar::f32;
  ran.steps_run = 300;
  // A message with a byte that is not UTF-8 (an engine's own text): replaced, not a broken file.
  ran.verdict.failures.push_back({FailureMode::frozen, "bob", 12, "held \xff still"});
  ran.search = searched(1.0 / 30.0, StepSearch::none, std::nullopt);  // no failure up to the cap
  ran.theory_max_dt = std::nullopt;
  EngineStability skipped;
  skipped.engine = "box2d";
  skipped.skipped = "no springs";
  s.engines = {ran, skipped};
  SearchOptions options;
  options.horizon_steps = 500;
  options.rel_tol = 0.01;

  const std::string text = stability_to_json(s, options);
  const nlohmann::json j = parse_json<nlohmann::json>(text);  // throws on invalid JSON
  CHECK(j["scene"] == "spring");
  CHECK(j["dt"].get<double>() == 1.0 / 30.0);  // every digit back
  CHECK_THAT(j["search_rule"].get<std::string>(),
             Contains("min(duration, 500*dt)") && Contains("to a relative 0.01"));
  REQUIRE(j["engines"].size() == 2);
  const nlohmann::json& e = j["engines"][0];
  CHECK(e["scalar"] == "f32");
  CHECK(e["verdict"] == "frozen");
  CHECK(e["failures"][0]["step"] == 12);
  CHECK(e["failures"][0]["message"] == "held \xef\xbf\xbd still");  // U+FFFD
  CHECK(e["max_stable_dt"].get<double>() == 1.0 / 30.0);
  CHECK(e["search"]["min_unstable_dt"].is_null());
  CHECK(e["search"]["limit"].is_null());
  CHECK(e["search"]["capped"] == true);
  CHECK(e["search"]["probes"] == 7);
  CHECK(e["theory_max_dt"].is_null());
  CHECK(e["error_vs_analytic"].is_null());
  CHECK(j["engines"][1] == nlohmann::json({{"engine", "box2d"}, {"skipped", "no springs"}}));
  // A search that found a failure is not capped; one without a search has nulls.
  s.engines[0].search = searched(0.033303, 0.0333481, FailureMode::unbounded_growth);
  CHECK(parse_json<nlohmann::json>(
            stability_to_json(s, options))["engines"][0]["search"]["capped"] == false);
  s.engines[0].search.reset();
  const nlohmann::json none = parse_json<nlohmann::json>(stability_to_json(s, options));
  CHECK(none["engines"][0]["max_stable_dt"].is_null());
  CHECK(none["engines"][0]["search"].is_null());
}

TEST_CASE("the study's text lists each engine once, then every failure under its label",
          "[stability][report]") {
  SceneStability s;
  s.name = "spring";
  s.h = {1.0 / 30.0, "1/30"};
  s.duration = 10.0;
  s.steps = 300;
  s.no_analytic = "contacts";
  EngineStability a;
  a.engine = "ours";
  a.scalar = Scalar::f32;
  a.verdict.failures = {{FailureMode::non_finite, "", 40, "NaN at step 40"},
                        {FailureMode::unbounded_growth, "bob", 20, "energy grew"}};
  a.theory_max_dt = 2.0 / 60.0;
  EngineStability b;
  b.engine = "box2d";
  b.skipped = "no springs";
  s.engines = {a, b};
  const std::string text = stability_to_text(s);
  CHECK_THAT(text, StartsWith("scene spring: h = 1/30 (300 steps over 10 s); analytic oracle: "
                              "contacts\n"));
  CHECK_THAT(text, Contains("ours (f32)       NaN/Inf           -              0.0333333"));
  CHECK_THAT(text, Contains("box2d            skipped: no springs\n"));
  CHECK_THAT(text, EndsWith("  ours (f32): NaN at step 40\n  ours (f32): energy grew\n"));
}
