// Tests harness/report/stability_report.cpp: the report section is Markdown with one column per
// known engine, byte-identical from run to run, runs only the engines passed in and names every
// failure (the JSON and text forms of a study: stability_io_test.cpp).
#include "harness/report/stability_report.hpp"

#include <catch2/catch.hpp>
#include <sstream>

#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "tests/engine_slots.hpp"
#include "tests/shipped_scenes.hpp"

using Catch::Matchers::Contains;
using namespace dropcheck;

using dropcheck::testing::slots;

TEST_CASE("The stability section runs only the engines passed in", "[stability][report]") {
  std::ostringstream progress;
  stability_report_section({kTinyStepScene}, slots({"ours"}), progress);
  CHECK(progress.str().find("ours") != std::string::npos);
  for (const std::string& other : available_engine_names())
    if (other.rfind("ours", 0) != 0)
      CHECK(progress.str().find(" " + other + " ") == std::string::npos);
}

TEST_CASE("The stability section is deterministic Markdown naming every failure",
          "[stability][report]") {
  std::ostringstream progress;
  const std::string a = stability_report_section({kTinyStepScene, kStiffSpringScene},
                                                 slots(available_engine_names()), progress);
  const std::string b = stability_report_section({kStiffSpringScene, kTinyStepScene},
                                                 slots(available_engine_names()), progress);
  CHECK(a == b);  // scenes sorted by name, no timings
  CHECK_THAT(a, Contains("## Stability: stiff and extreme cases"));
  std::string header = "| scene | h |";
  for (const std::string& e : known_engine_names()) header += " " + e + " |";
  CHECK_THAT(a, Contains(header));
  CHECK_THAT(a, Contains("| `stiff_spring` | 1/32 | stable |"));
  CHECK_THAT(
      a, Contains(
             "- `tiny_step`, ours (f32), frozen: body 'at_10m': position frozen at y = 10.000000"));
  CHECK_THAT(a, Contains("0.0333 (unbounded growth) / 0.03333"));  // ours: measured / theory
  CHECK_THAT(progress.str(), Contains("stability tiny_step: ours (f32) frozen"));
}

TEST_CASE("Stability: a bad scene file is an InputError naming it", "[stability][report]") {
  std::ostringstream progress;
  CHECK_THROWS_AS(stability_report_section({"/nonexistent/x.toml"}, slots({"ours"}), progress),
                  InputError);
}
