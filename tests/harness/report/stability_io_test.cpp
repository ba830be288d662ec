// Tests harness/report/stability_io.cpp: the JSON and text forms of a stability study carry the
// verdicts, the search's result and the skipped engines.
#include "harness/report/stability_io.hpp"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "harness/core/registry.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/stability_study.hpp"

using Catch::Matchers::Contains;
using namespace dropcheck;

namespace {

const std::string kTiny = DROPCHECK_SOURCE_DIR "/scenarios/extreme/tiny_step.toml";

// Engine slots for `names`, as the command line makes them (harness/cli/cmd_report.cpp).
std::vector<EngineSlot> slots(const std::vector<std::string>& names) {
  std::vector<EngineSlot> out;
  for (const std::string& name : names) {
    const std::string why = engine_unavailable_reason(name);
    out.push_back(
        {name, why.empty() ? EngineFactory([name] { return make_engine(name); }) : EngineFactory(),
         why});
  }
  return out;
}

}  // namespace

TEST_CASE("Stability: the study's JSON and text carry verdicts, the search and skipped engines",
          "[stability][report]") {
  const Scene scene = load_scene(kTiny);
  const SceneStability s = study_scene(scene, slots({"ours", "ours-f64"}));
  const std::string json = stability_to_json(s, StudyOptions{}.search_options);
  CHECK_THAT(json, Contains("\"engine\":\"ours\",\"scalar\":\"f32\"") &&
                       Contains("\"verdict\":\"frozen\""));
  CHECK_THAT(json, Contains("\"min_stable_dt\":") && Contains("\"max_stable_dt\":"));
  const std::string text = stability_to_text(s);
  CHECK_THAT(text, Contains("ours (f32)       frozen") && Contains("frozen below"));
  const SceneStability floor =
      study_scene(load_scene(DROPCHECK_SOURCE_DIR "/scenarios/extreme/thin_floor.toml"),
                  slots({"ours"}), StudyOptions{});
  CHECK(floor.engines.front().skipped == "no contacts");
  CHECK_THAT(stability_to_json(floor, {}),
             Contains("{\"engine\":\"ours\",\"skipped\":\"no contacts\"}"));
}
