// Tests harness/baseline*.cpp and harness/guard/bless.cpp: the baseline text format round-trips to
// the bit, malformed files are named precisely, and bless refuses a run that is wrong physics.
#include "harness/guard/baseline.hpp"

#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>

#include "../moved_drag_engine.hpp"
#include "../test_dirs.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/guard/baseline_io.hpp"
#include "harness/guard/baseline_parse.hpp"
#include "harness/guard/bless.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/engine_slots.hpp"

using namespace dropcheck;
using namespace dropcheck::testing;

namespace {

std::uint64_t bits(double v) {
  return std::bit_cast<std::uint64_t>(v);
}

// Every number of the two baselines, compared as bit patterns (NaN included).
void require_same_bits(const Baseline& a, const Baseline& b) {
  REQUIRE(a.samples.recorded == b.samples.recorded);
  REQUIRE(a.samples.states.size() == b.samples.states.size());
  for (std::size_t i = 0; i < a.samples.states.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      REQUIRE(bits(a.samples.states[i].position[c]) == bits(b.samples.states[i].position[c]));
      REQUIRE(bits(a.samples.states[i].velocity[c]) == bits(b.samples.states[i].velocity[c]));
    }
  }
  REQUIRE(a.sweep.size() == b.sweep.size());
  for (std::size_t i = 0; i < a.sweep.size(); ++i) {
    REQUIRE(bits(a.sweep[i].dt.seconds) == bits(b.sweep[i].dt.seconds));
    REQUIRE(bits(a.sweep[i].analytic_max_dx) == bits(b.sweep[i].analytic_max_dx));
    REQUIRE(bits(a.sweep[i].analytic_final_dx) == bits(b.sweep[i].analytic_final_dx));
    REQUIRE(bits(a.sweep[i].law_max_dx) == bits(b.sweep[i].law_max_dx));
    REQUIRE(bits(a.sweep[i].wall_min) == bits(b.sweep[i].wall_min));
    REQUIRE(bits(a.sweep[i].wall_median) == bits(b.sweep[i].wall_median));
  }
  REQUIRE(bits(a.dt.seconds) == bits(b.dt.seconds));
}

// Blesses free_fall_drag into `dir` with ours-f64 whose drag is moved (tests/harness/
// moved_drag_engine.hpp), a run that breaks its own law; `refuse_failed` as BlessOptions'.
BlessOutcome bless_moved_drag(const ScratchDir& dir, bool refuse_failed) {
  BlessOptions options;
  options.out_dir = dir.path.string();
  options.refuse_failed = refuse_failed;
  return bless({shipped_scene("free_fall_drag")}, {{"ours-f64", make_moved_drag_f64}}, options);
}

}  // namespace

TEST_CASE("A baseline written as text reads back to the bit", "[baseline]") {
  const Baseline made = make_baseline(shipped_scene("wind"), testing::factory("ours-f64"));
  const std::string text = baseline_to_text(made);
  const Baseline read = parse_baseline(text, "wind.ours-f64.txt");
  require_same_bits(made, read);
  CHECK(read.hash == made.hash);
  CHECK(read.build_keys == made.build_keys);
  CHECK(read.samples.body_names == std::vector<std::string>{"medium", "small"});
  CHECK(read.samples.recorded.back() == 120);  // every 10th step and the last
  CHECK(baseline_to_text(read) == text);
}

TEST_CASE("Awkward numbers survive the text format exactly", "[baseline]") {
  Baseline b = make_baseline(shipped_scene("free_fall"), testing::factory("ours"));
  BodyState& s = b.samples.states[1];
  s.position = Vec3(-0.0, 4.9406564584124654e-324, 0.1);  // negative zero, smallest denormal
  s.velocity = Vec3(1.0 / 3.0, -1.7976931348623157e308, 2.2250738585072014e-308);
  b.sweep[0].analytic_max_dx = kNoValue;  // "no closed form" is NaN
  b.sweep[1].wall_min = 1.0 / 7.0;        // timing present on one h only
  b.sweep[1].wall_median = 0.3;
  b.sweep[1].replicas = 64;
  const Baseline read = parse_baseline(baseline_to_text(b), "awkward.txt");
  require_same_bits(b, read);
  CHECK(std::signbit(read.samples.states[1].position.x()));
  CHECK(read.sweep[1].replicas == 64);
  CHECK(std::isnan(read.sweep[0].wall_min));
}

TEST_CASE("A malformed baseline names the file, line and record", "[baseline]") {
  const std::string good =
      baseline_to_text(make_baseline(shipped_scene("free_fall"), testing::factory("ours-f64")));
  std::string bad = good;
  bad.replace(bad.find("sample 10 cube 0 "), 17, "sample 10 cube 0x ");
  REQUIRE_THROWS_WITH(parse_baseline(bad, "x.txt"),
                      Catch::Contains("x.txt:") && Catch::Contains("not a number: '0x'"));
  REQUIRE_THROWS_WITH(parse_baseline(good + "colour blue\n", "y.txt"),
                      Catch::Contains("unknown record 'colour'"));
  std::string many_keys = good;
  for (std::size_t k = 0; k < kMaxBuildKeys; ++k)
    many_keys.insert(many_keys.find("scene "), "build_key b" + std::to_string(k) + "\n");
  REQUIRE_THROWS_WITH(parse_baseline(many_keys, "k.txt"),
                      Catch::Contains("k.txt:18") && Catch::Contains("build_key") &&
                          Catch::Contains("more than 16 build keys"));
  REQUIRE_THROWS_WITH(read_baseline("/nonexistent/z.txt"),
                      Catch::Contains("run `dropcheck bless`"));
}

TEST_CASE("An engine that cannot run a scene leaves a skipped baseline with its reason",
          "[baseline]") {
  const Scene scene = load_scene(kTurnedPair);
  const Baseline b = make_baseline(scene, testing::factory("ours"));
  const std::string why =
      "a turned or turning box beside another dynamic body or a static sphere: ours collides a "
      "turned box only with static boxes (its corners against their faces)";
  CHECK(b.skipped == why);
  CHECK(b.analytic.rfind("none: contacts", 0) == 0);
  const Baseline read = parse_baseline(baseline_to_text(b), "ours_turned_pair.ours.txt");
  CHECK(read.skipped == why);
  CHECK(read.samples.samples() == 0);
}

TEST_CASE(
    "Bless into the golden set refuses a run that breaks its own discrete law and writes nothing",
    "[baseline][bless]") {
  const ScratchDir dir("bless-refuses");
  const BlessOutcome out = bless_moved_drag(dir, true);  // refused as for tests/baselines
  REQUIRE(out.refused.size() == 1);
  INFO(out.refused[0]);
  CHECK_THAT(out.refused[0],
             Catch::StartsWith("free_fall_drag / ours-f64 / physics: oracle 2 (own discrete law"));
  CHECK_THAT(out.refused[0], Catch::Contains("body 'cube' departs from it by"));
  CHECK_THAT(out.refused[0], Catch::Contains("from step 1 on"));
  CHECK(out.lines.empty());
  CHECK(std::filesystem::is_empty(dir.path));
}

TEST_CASE(
    "Bless --out elsewhere writes a run that breaks its law, the failed tier marked in the file",
    "[baseline][bless]") {
  const ScratchDir dir("bless-marks");
  CHECK_FALSE(is_golden_set(dir.path.string()));
  CHECK(is_golden_set("tests/baselines"));
  const BlessOutcome out = bless_moved_drag(dir, false);
  CHECK(out.refused.empty());
  REQUIRE(out.lines.size() == 1);
  CHECK_THAT(out.lines[0],
             Catch::Contains("FAILED physics: free_fall_drag / ours-f64 / physics: oracle 2"));
  const std::string text = slurp(dir.file("free_fall_drag.ours-f64.txt"));
  CHECK_THAT(text, Catch::Contains("\n# FAILED physics: "));
  CHECK(parse_baseline(text, "x").hash.size() > 0);  // still a baseline `diff` can read
  // The same numbers from another build: its key is added and the FAILED mark stays.
  std::string other = text;
  const std::size_t key = other.find("build_key ");
  other.replace(key, other.find('\n', key) - key, "build_key x86_64, GNU 99.0.0, -O3");
  dir.write("free_fall_drag.ours-f64.txt", other);
  const BlessOutcome again = bless_moved_drag(dir, false);
  REQUIRE(again.lines.size() == 1);
  CHECK_THAT(again.lines[0], Catch::StartsWith("same data "));
  const std::string both = slurp(dir.file("free_fall_drag.ours-f64.txt"));
  CHECK_THAT(both, Catch::Contains("\n# FAILED physics: ") &&
                       Catch::Contains("build_key x86_64, GNU 99.0.0, -O3\nbuild_key "));
  CHECK_THAT(bless_moved_drag(dir, false).lines[0], Catch::StartsWith("unchanged "));
}

TEST_CASE("Bless writes every baseline and leaves unchanged data byte for byte",
          "[baseline][bless]") {
  const ScratchDir dir("bless-writes");
  BlessOptions options;
  options.out_dir = dir.path.string();
  options.commit = "aaaaaaa 2026-01-01";
  const std::vector<Scene> scenes = {shipped_scene("free_fall"), load_scene(kTurnedPair)};
  const std::vector<NamedFactory> engines = {{"ours", testing::factory("ours")},
                                             {"ours-f64", testing::factory("ours-f64")}};
  const BlessOutcome first = bless(scenes, engines, options);
  REQUIRE(first.refused.empty());
  REQUIRE(first.lines.size() == 4);
  CHECK_THAT(first.lines[0],
             Catch::StartsWith("new ") && Catch::Contains("free_fall.ours.txt (hash "));
  CHECK_THAT(first.lines[2],
             Catch::Contains("ours_turned_pair.ours.txt (skipped: a turned or turning box"));
  const std::string before = slurp(dir.file("free_fall.ours.txt"));
  CHECK_THAT(before, Catch::StartsWith("# dropcheck baseline: made by `dropcheck bless` with ") &&
                         Catch::Contains("on commit aaaaaaa 2026-01-01\n"));

  options.commit = "bbbbbbb 2026-02-02";  // a later commit, same numbers: nothing is rewritten
  const BlessOutcome second = bless(scenes, engines, options);
  CHECK_THAT(second.lines[0], Catch::StartsWith("unchanged "));
  CHECK(slurp(dir.file("free_fall.ours.txt")) == before);

  // A file another build made with the same numbers (measured: GCC 12 and Clang 14, each at -O2
  // with sanitizers, agree to the bit on every shipped baseline) gains this build's key after the
  // other's, the rest byte for byte; a second bless leaves it. New numbers keep one key only.
  std::string other_build = before;
  const std::size_t key = other_build.find("build_key ");
  const std::size_t key_end = other_build.find('\n', key);
  const std::string this_key = other_build.substr(key, key_end - key);
  other_build.replace(key, key_end - key, "build_key x86_64, GNU 99.0.0, -O3");
  CHECK(same_data(before, other_build));
  CHECK_FALSE(same_data(before, std::string(before).replace(before.find("hash "), 6, "hash 0")));
  dir.write("free_fall.ours.txt", other_build);
  const BlessOutcome third = bless(scenes, engines, options);
  CHECK_THAT(third.lines[0], Catch::StartsWith("same data ") &&
                                 Catch::Contains("build key added: " + this_key.substr(10)));
  const std::string both = slurp(dir.file("free_fall.ours.txt"));
  CHECK(both == std::string(other_build).insert(other_build.find('\n', key) + 1, this_key + "\n"));
  CHECK(parse_baseline(both, "x").build_keys.size() == 2);
  CHECK_THAT(bless(scenes, engines, options).lines[0], Catch::StartsWith("unchanged "));
  dir.write("free_fall.ours.txt",
            std::string(other_build).replace(other_build.find("hash "), 6, "hash 0"));
  CHECK_THAT(bless(scenes, engines, options).lines[0], Catch::StartsWith("updated "));
  const Baseline fresh = parse_baseline(slurp(dir.file("free_fall.ours.txt")), "x");
  CHECK(fresh.build_keys == std::vector<std::string>{this_key.substr(10)});
}
