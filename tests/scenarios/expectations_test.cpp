// Tests that no figure a shipped scene's description states goes unchecked (docs/design.md,
// "Scenario files"). Each entry of a scene's [expect] table, which its description quotes as
// {name}, is a quantity the harness computes from the scene (tests/scenarios/quantities.hpp) and
// agrees with it to the precision written: half a unit in the last digit. Every figure the
// description writes itself is a number the scene file sets (tests/scenarios/literal_figures.hpp).
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "harness/scene/scene_loader.hpp"
#include "tests/scenarios/literal_figures.hpp"
#include "tests/scenarios/quantities.hpp"
#include "tests/scene_texts.hpp"
#include "tests/shipped_scenes.hpp"

namespace {

using dropcheck::ExpectedFigure;
using dropcheck::Scene;
using dropcheck::testing::Quantity;

// Half a unit in the last digit written: "1.919" -> 5e-4, "1e-5" -> 5e-6, "60" -> 0.5.
double half_unit(const std::string& text) {
  const std::size_t e = text.find('e');
  const std::string mantissa = text.substr(0, e);
  const int exponent = e == std::string::npos ? 0 : std::stoi(text.substr(e + 1));
  const std::size_t dot = mantissa.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(mantissa.size() - dot - 1);
  return 0.5 * std::pow(10.0, exponent - decimals);
}

// "" when `figure` rounds `value` (within half a unit of its last digit, plus 1e-9 relative for
// values such as 1/(1/60) that are exact in decimal but not in binary); else what disagrees.
std::string agrees(const ExpectedFigure& figure, double value) {
  const double tol = half_unit(figure.text) * (1.0 + 1e-9) + 1e-9 * std::abs(figure.value);
  if (std::abs(value - figure.value) <= tol) return "";
  std::ostringstream out;
  out.precision(7);
  out << "states " << figure.text << ", the scene gives " << value;
  return out.str();
}

// The problem of a body's quantity stated for body `body` ("": at the top of [expect], for every
// body it applies to), or "".
std::string body_problem(const Scene& s, const Quantity& q, const std::string& body,
                         const ExpectedFigure& figure) {
  bool applies = false;
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    if (!body.empty() && s.bodies[i].name != body) continue;
    const std::optional<double> value = q.of_body(s, i);
    if (!value) continue;
    applies = true;
    if (std::string p = agrees(figure, *value); !p.empty())
      return body.empty() ? "body \"" + s.bodies[i].name + "\" " + p : p;
  }
  if (applies) return "";
  return body.empty() ? "applies to no body of the scene"
                      : "does not apply to body \"" + body + "\"";
}

// The problem of the [expect] entry `key` ("name" or "body.name"), or "".
std::string entry_problem(const Scene& s, const std::string& key, const ExpectedFigure& figure) {
  const std::size_t dot = key.find('.');
  const std::string body = dot == std::string::npos ? "" : key.substr(0, dot);
  const std::string name = dot == std::string::npos ? key : key.substr(dot + 1);
  const auto q = dropcheck::testing::quantities().find(name);
  if (q == dropcheck::testing::quantities().end())
    return "no quantity is named \"" + name + "\" (tests/scenarios/quantities.hpp)";
  if (q->second.of_body) return body_problem(s, q->second, body, figure);
  if (!body.empty()) return "\"" + name + "\" is the scene's, not a body's: write it in [expect]";
  const std::optional<double> value = q->second.of_scene(s);
  return value ? agrees(figure, *value) : "does not apply to this scene";
}

// Every [expect] entry of `s` that is no known quantity or disagrees with it, as
// "expect.KEY: PROBLEM".
std::vector<std::string> expectation_problems(const Scene& s) {
  std::vector<std::string> problems;
  for (const auto& [key, figure] : s.expect)
    if (std::string p = entry_problem(s, key, figure); !p.empty())
      problems.push_back("expect." + key + " = " + figure.text + ": " + p);
  return problems;
}

Scene scene_of(const std::string& text) {
  return dropcheck::parse_scene(text, "x.toml");
}

// A slide of slide_stop.toml: stops at step 62 after 2.509472 m at h = 1/60.
std::string slide(const std::string& description, const std::string& expect) {
  using namespace dropcheck::testing;
  return "description = \"" + description + "\"\n" + scene_head("4.0", "1/60", kEarth) +
         "contacts = true\n" + expect +
         body_text("cube", "[0.0, 0.5, 0.0]", "[5.0, 0.0, 0.0]", "friction = 0.5\n") +
         body_text("floor", "[0.0, -0.5, 0.0]", "",
                   "static = true\nhalf_extents = [20.0, 0.5, 20.0]\n");
}

}  // namespace

TEST_CASE("every [expect] figure of a shipped scene is a quantity the harness computes from it",
          "[scenarios][expectations]") {
  const std::vector<std::string> files = shipped_scenes();
  REQUIRE(files.size() >= 33);  // 20 scenes in scenarios/, 13 in scenarios/extreme/
  for (const std::string& file : files) {
    const Scene scene = dropcheck::load_scene(file);
    INFO(file << ": " << scene.description);
    CHECK_FALSE(scene.description.empty());
    for (const std::string& problem : expectation_problems(scene)) {
      INFO(problem);
      CHECK(problem.empty());  // prints the problem
    }
  }
}

TEST_CASE("every figure a shipped description writes itself is a number its scene file sets",
          "[scenarios][expectations]") {
  for (const std::string& file : shipped_scenes()) {
    INFO(file);
    for (const std::string& problem :
         dropcheck::testing::literal_figure_problems(dropcheck::read_scene_text(file), file)) {
      INFO(problem);
      CHECK(problem.empty());  // prints the problem
    }
  }
}

TEST_CASE("an [expect] figure that disagrees, is unknown or is misplaced is refused, naming it",
          "[scenarios][expectations]") {
  const std::string at = "stops at step {law_stop_step}";
  CHECK(expectation_problems(scene_of(slide(at, "[expect]\nlaw_stop_step = 62\n"))).empty());
  // 1.0204 s to the precision written; 1.02 rounds it, 1.0200 claims a digit that is not so.
  const std::string in = "stops after {stop_time} s";
  CHECK(expectation_problems(scene_of(slide(in, "[expect]\nstop_time = 1.02\n"))).empty());
  CHECK(expectation_problems(scene_of(slide(in, "[expect]\nstop_time = 1.0200\n"))).size() == 1);

  std::vector<std::string> p =
      expectation_problems(scene_of(slide(at, "[expect]\nlaw_stop_step = 63\n")));
  REQUIRE(p.size() == 1);
  CHECK(p[0] == "expect.law_stop_step = 63: body \"cube\" states 63, the scene gives 62");

  p = expectation_problems(scene_of(slide("{stop_stp}", "[expect]\nstop_stp = 62\n")));
  REQUIRE(p.size() == 1);
  CHECK_THAT(p[0], Catch::Contains("expect.stop_stp = 62: no quantity is named \"stop_stp\""));

  // A body's quantity under another body, and a scene's quantity under a body.
  p = expectation_problems(
      scene_of(slide("{floor.law_stop_step}", "[expect.floor]\nlaw_stop_step = 62\n")));
  REQUIRE(p.size() == 1);
  CHECK_THAT(p[0], Catch::Contains("does not apply to body \"floor\""));
  p = expectation_problems(scene_of(slide("{cube.steps}", "[expect.cube]\nsteps = 240\n")));
  REQUIRE(p.size() == 1);
  CHECK_THAT(p[0], Catch::Contains("the scene's, not a body's"));
}

TEST_CASE("a body's quantity at the top of [expect] must hold for every body it applies to",
          "[scenarios][expectations]") {
  // Two cubes thrown up at 8 and 4 m/s: their apexes differ, so apex_time names a body.
  using namespace dropcheck::testing;
  const auto two = [](const std::string& description, const std::string& expect) {
    return "description = \"" + description + "\"\n" + scene_head("2.0", "1/60", kEarth) + expect +
           body_text("fast", kZero, "[0.0, 8.0, 0.0]") +
           body_text("slow", "[3.0, 0.0, 0.0]", "[0.0, 4.0, 0.0]");
  };
  std::vector<std::string> p =
      expectation_problems(scene_of(two("{apex_time}", "[expect]\napex_time = 0.816\n")));
  REQUIRE(p.size() == 1);
  CHECK_THAT(p[0], Catch::Contains("body \"slow\" states 0.816, the scene gives 0.408"));
  CHECK(expectation_problems(scene_of(two("{fast.apex_time} {slow.apex_time}",
                                          "[expect.fast]\napex_time = 0.816\n"
                                          "[expect.slow]\napex_time = 0.408\n")))
            .empty());
  CHECK(expectation_problems(scene_of(two("{rise}", "[expect]\nrise = 1\n")))[0] ==
        "expect.rise = 1: body \"fast\" states 1, the scene gives 3.265306");
}

TEST_CASE("a figure a description writes itself must be a number its scene file sets",
          "[scenarios][expectations]") {
  const auto problems = [](const std::string& description) {
    return dropcheck::testing::literal_figure_problems(slide(description, ""), "x.toml");
  };
  // Inputs as the file writes them: 5 m/s, mu = 0.5, 9.8 (gravity's magnitude), h = 1/60 and its
  // 60 Hz, 4 s. Not figures: a digit in a name, a unit's power, the 1 of 1/s.
  CHECK(problems("launched at 5 m/s, mu = 0.5, a gravity of 9.8 m/s^2, h = 1/60 (60 Hz), 4 s, "
                 "Box2D, k in 1/s (docs/engines.md section 5)")
            .empty());
  std::vector<std::string> p = problems("it stops after 1.0204 s");  // computed, not an input
  REQUIRE(p.size() == 1);
  CHECK_THAT(p[0],
             Catch::Contains("\"1.0204\" in the description is no number the scene file sets"));
  CHECK(problems("gravity -9.8").empty());
  CHECK(problems("launched at -5 m/s").size() == 1);  // signed: the input itself, 5
  CHECK(problems("at h = 1/30").size() == 1);
  CHECK(problems("a placeholder's figure is checked by its quantity: {law_stop_step}").empty());
  p = problems("see docs/engines.md section 99");
  REQUIRE(p.size() == 1);
  CHECK_THAT(p[0], Catch::Contains("section 99, which docs/engines.md does not have"));
}
