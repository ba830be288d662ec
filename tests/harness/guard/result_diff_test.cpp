// Tests harness/guard/result_diff.cpp: `dropcheck diff` on two result sets, one of them made by an
// integrator with the damping moved after the position update (moved_drag_engine.hpp).
#include "harness/guard/result_diff.hpp"

#include <catch2/catch.hpp>

#include "../../engine_slots.hpp"
#include "../moved_drag_engine.hpp"
#include "../test_dirs.hpp"
#include "harness/guard/baseline_io.hpp"
#include "harness/io/atomic_file.hpp"

using namespace dropcheck;
using namespace dropcheck::testing;

namespace {

void write_baseline_file(const ScratchDir& dir, const Baseline& b) {
  write_file_atomic(dir.file(baseline_file_name(b.scene, b.engine)), baseline_to_text(b));
}

// Both sides are test doubles, so that the pinned rows do not move when ours does.
EngineFactory ours_f64 = make_seed_order_f64;

}  // namespace

TEST_CASE("Diff of two result sets lists what moved and how the error curves shifted",
          "[baseline][diff]") {
  const ScratchDir before("diff-before"), after("diff-after");
  for (const char* stem : {"free_fall", "free_fall_drag"})
    write_baseline_file(before, make_baseline(shipped_scene(stem), ours_f64));
  write_baseline_file(
      before, make_baseline(shipped_scene("throw_up"), ours_f64));  // dropped from the new set
  write_baseline_file(
      after, make_baseline(shipped_scene("free_fall"), make_moved_drag_f64));  // f = 1: no change
  write_baseline_file(after, make_baseline(shipped_scene("free_fall_drag"), make_moved_drag_f64));

  const std::string md =
      diff_markdown(load_result_set(before.path.string()), load_result_set(after.path.string()));
  INFO(md);
  CHECK_THAT(
      md,
      Catch::Contains(
          "1 of 3 scene/engine runs moved beyond tolerance (1e-09 m for f64, 0.0001 m for f32)"));
  CHECK_THAT(md,
             Catch::Contains("| free_fall | ours-f64 | identical | 0 m | - (tolerance 1e-09 m) |"));
  CHECK_THAT(md,
             Catch::Contains(
                 "| free_fall_drag | ours-f64 | **moved** | 0.0696 m (step 60) | step 10, cube.y: "
                 "9.86173341 -> 9.85891164 (0.00282) |"));
  CHECK_THAT(md, Catch::Contains("| throw_up | ours-f64 | only before | - | - | - |"));
  // The curve: with the drag after the position update the cube moves with the velocity before
  // damping each step, falls faster, and ends 4 times farther from the continuous solution.
  CHECK_THAT(md, Catch::Contains("| free_fall_drag | ours-f64 | 1/60 | 0.0203 | 0.0821 | 4.05 |"));
  CHECK_THAT(md, Catch::Contains("The result sets carry no timing"));
  CHECK_THAT(md, Catch::Contains("4 points with identical errors omitted."));
}

TEST_CASE("Diff shows wall time per simulated second when the result sets carry timing",
          "[baseline][diff]") {
  const ScratchDir before("timing-before"), after("timing-after");
  Baseline b = make_baseline(shipped_scene("free_fall"), ours_f64);
  for (SweepPoint& p : b.sweep) p.wall_min = 1e-3, p.wall_median = 1.1e-3, p.replicas = 8;
  write_baseline_file(before, b);
  for (SweepPoint& p : b.sweep) p.wall_min = 2.5e-3;
  write_baseline_file(after, b);
  const std::string md =
      diff_markdown(load_result_set(before.path.string()), load_result_set(after.path.string()));
  INFO(md);
  CHECK_THAT(md, Catch::Contains(
                     "| error before | error after | after/before | wall before | wall after |"));
  CHECK_THAT(md,
             Catch::Contains("| free_fall | ours-f64 | 1/60 | 0.0817 | 0.0817 | 1 | 1 | 2.5 |"));
}

TEST_CASE("Diff refuses a result set that is not a directory", "[baseline][diff]") {
  REQUIRE_THROWS_WITH(load_result_set("/nonexistent/set"),
                      Catch::Contains("not a directory of baseline files"));
}

TEST_CASE("Diff says what moved in contact terms: a slide's stop step, a bounce's apexes",
          "[baseline][diff][contact]") {
  // ours with a friction bug (mu 10 % high) and a restitution bug (e 10 % high), blessed under the
  // shipped scenes' names.
  const ScratchDir before("diff-contact-before"), after("diff-contact-after");
  Scene slide = shipped_scene("slide_stop"), bounce = shipped_scene("bounce_e05");
  for (const Scene* s : {&slide, &bounce})
    write_baseline_file(before, make_baseline(*s, factory("ours-f64")));
  for (Body& b : slide.bodies)
    if (b.friction) *b.friction *= 1.1;
  for (Body& b : bounce.bodies)
    if (b.restitution) *b.restitution *= 1.1;
  for (const Scene* s : {&slide, &bounce})
    write_baseline_file(after, make_baseline(*s, factory("ours-f64")));
  const ResultSet a = load_result_set(after.path.string());
  CHECK(a.runs.at("slide_stop.ours-f64.txt").contact.size() == 2);  // read back from the file
  const std::string md = diff_markdown(load_result_set(before.path.string()), a);
  INFO(md);
  // The clamp law: 5 m/s against mu*g*h = 0.08167 m/s a step stops at step 62 (0.0898 at 0.55:
  // step 56).
  CHECK_THAT(md, Catch::Contains("| slide_stop | ours-f64 | cube.stop_step | 62 -> 56 |"));
  CHECK_THAT(md, Catch::Contains("| slide_stop | ours-f64 | cube.distance | 2.509472 m -> "));
  CHECK_THAT(md, Catch::Contains("| bounce_e05 | ours-f64 | ball.apex_1 | 0.2667"));
  // The first contact does not move with e.
  CHECK_THAT(md, Catch::Contains("(1 figure identical)"));
  CHECK_THAT(md, !Catch::Contains("ball.contact_step |"));
}
