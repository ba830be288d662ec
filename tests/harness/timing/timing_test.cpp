// Tests harness/timing/timing.cpp: replication keeps the physics of every copy, and timing returns
// figures. No timing thresholds: wall times depend on the machine and its load, and such tests
// flake.
#include "harness/timing/timing.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <variant>

#include "harness/core/registry.hpp"
#include "harness/run/runner.hpp"

using namespace dropcheck;

namespace {

// A floor, a cube pushed by a constant force and a cube on a spring, all in the x-y plane.
Scene timing_scene() {
  Scene s;
  s.name = "timing";
  s.duration = 0.5;
  s.world = {.gravity = {0.0, -9.8, 0.0}, .damping_rate = 0.5};
  s.bodies = {{.name = "floor",
               .half_extents = {5.0, 0.5, 5.0},
               .position = {0.0, -0.5, 0.0},
               .is_static = true},
              {.name = "pushed", .position = {-2.0, 6.0, 0.0}},
              {.name = "sprung", .position = {2.0, 4.0, 0.0}, .velocity = {0.5, 1.0, 0.0}}};
  s.forces = {{{1}, ConstantForce{{2.0, 0.0, 0.0}}},
              {{2}, Spring{{2.0, 5.0, 0.0}, 40.0, 0.3, 0.0}}};
  return s;
}

// A factory of ours that appends `tag` to `made` each time it makes one: the order engines ran in.
EngineFactory tagged_ours(std::string& made, char tag) {
  return [&made, tag] {
    made += tag;
    return make_engine("ours");
  };
}

}  // namespace

TEST_CASE("timing replicates every body and force, shifted along x", "[timing]") {
  const Scene s = timing_scene();
  const Scene r = replicate(s, 3);
  REQUIRE(r.bodies.size() == 9);
  REQUIRE(r.forces.size() == 6);
  const double shift = 10.0 + 10.0;  // x extent of the scene (floor: -5 .. 5) + 10 m
  for (int c = 1; c < 3; ++c) {
    for (std::size_t i = 0; i < 3; ++i) {
      const Body& copy = r.bodies[3 * c + i];
      CHECK(copy.name == s.bodies[i].name + "#" + std::to_string(c));
      CHECK(copy.position == s.bodies[i].position + Vec3(shift * c, 0.0, 0.0));
      CHECK(copy.velocity == s.bodies[i].velocity);
      CHECK(copy.is_static == s.bodies[i].is_static);
    }
    const Force &push = r.forces[2 * c], &spring = r.forces[2 * c + 1];
    CHECK(push.bodies == std::vector<std::size_t>{3u * c + 1});
    CHECK(std::get<ConstantForce>(push.law).force == Vec3(2.0, 0.0, 0.0));
    CHECK(spring.bodies == std::vector<std::size_t>{3u * c + 2});
    CHECK(std::get<Spring>(spring.law).anchor == Vec3(2.0 + shift * c, 5.0, 0.0));
  }
  CHECK(is_planar(r));  // Box2D can time a replicated planar scene
  CHECK(replicate(s, 1).bodies.size() == 3);
  // A torque acts on each copy of its bodies too.
  Scene twisted = s;
  twisted.torques.push_back({{1}, Vec3(0.0, 0.0, 2.0)});
  const Scene t = replicate(twisted, 3);
  REQUIRE(t.torques.size() == 3);
  for (int c = 0; c < 3; ++c) CHECK(t.torques[c].bodies == std::vector<std::size_t>{1u + 3u * c});
}

TEST_CASE("every copy of a scene replicated for timing moves like the original", "[timing]") {
  const Scene s = timing_scene();
  const double h = 1.0 / 60, shift = 20.0;
  auto engine = make_engine("ours-f64");
  const Trajectory one = run_scene(*engine, s, h), three = run_scene(*engine, replicate(s, 3), h);
  REQUIRE(three.status == RunStatus::ok);
  double worst = 0.0;
  for (std::size_t n = 0; n < one.samples(); ++n)
    for (int c = 1; c < 3; ++c)
      for (std::size_t i = 0; i < 3; ++i) {
        const Vec3 moved = three.at(n, 3 * c + i).position - Vec3(shift * c, 0.0, 0.0);
        worst = std::max(worst, (moved - one.at(n, i).position).norm());
      }
  CHECK(worst < 1e-12);  // measured 9.3e-15 m: only the rounding of x + 20 m and x + 40 m
}

TEST_CASE("timing returns positive figures for every engine", "[timing]") {
  const Scene s = timing_scene();
  TimingOptions fast;  // as little work as possible: this checks the plumbing, not the machine
  fast.min_run_seconds = 0.0;
  fast.min_sample_seconds = 0.0;
  fast.warmups = 0;
  fast.samples = 4;
  const std::vector<std::pair<std::string, EngineFactory>> engines{
      {"ours", [] { return make_engine("ours"); }},
      {"ours-f64", [] { return make_engine("ours-f64"); }}};
  const std::vector<Timing> t = time_engines(engines, s, 1.0 / 60, fast);
  REQUIRE(t.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(t[i].engine == engines[i].first);
    CHECK(t[i].h == 1.0 / 60);
    CHECK(t[i].replicas == 1);
    CHECK(t[i].repeats == 1);
    CHECK(t[i].samples() == 4);
    REQUIRE(t[i].bare.size() == 4);
    REQUIRE(t[i].calibration.size() == 4);  // one calibration loop in each timed round
    CHECK(t[i].headline() > 0.0);
    CHECK(t[i].of(Statistic::q25) >= t[i].headline());
    CHECK(t[i].of(Statistic::median) >= t[i].of(Statistic::q25));
    CHECK(t[i].bare_of(Statistic::min) > 0.0);
    CHECK(t[i].ratio() > 0.0);
  }
  // Both engines were timed against the same calibration rounds.
  CHECK(t[0].calibration == t[1].calibration);
  for (double c : t[0].calibration) {
    CHECK(c > 0.0);
    CHECK(c < 1.0);
  }
}

TEST_CASE("the work of a timed run depends on the scene, h and engine name, never on a measurement",
          "[timing]") {
  const Scene s = timing_scene();  // 2 dynamic bodies, 0.5 s, no contacts
  TimingOptions o;
  o.min_run_seconds = 1e-5;
  // ours at 3.5 ns, 1/60: 30 steps * 2 bodies = 60 body-steps, 210 ns per copy; 32 copies last
  // 6.7 us < 10 us, 64 last 13.4 us.
  CHECK(replicas_for(s, 1.0 / 60, "ours", o) == 64);
  // 1/240: 240 body-steps, 840 ns per copy; 8 copies last 6.7 us, 16 last 13.4 us.
  CHECK(replicas_for(s, 1.0 / 240, "ours", o) == 16);
  // bullet at 580 ns: one copy lasts 34.8 us already; an unlisted engine (1000 ns) too.
  CHECK(replicas_for(s, 1.0 / 60, "bullet", o) == 1);
  CHECK(replicas_for(s, 1.0 / 60, "exec:python3 engine.py", o) == 1);
  o.max_replicas = 4;
  CHECK(replicas_for(s, 1.0 / 60, "ours", o) == 4);
  o.min_run_seconds = 1e-7;
  CHECK(replicas_for(s, 1.0 / 60, "ours", o) == 1);
  // A scene of static bodies only counts as one body, so it is still timed on enough steps.
  Scene still = s;
  for (Body& b : still.bodies) b.is_static = true;
  still.forces.clear();
  o.max_replicas = 4096;
  o.min_run_seconds = 1e-5;
  CHECK(replicas_for(still, 1.0 / 60, "ours", o) == 128);  // 105 ns per copy: 128 last 13.4 us
  // With contacts, the engine's contact cost: ours at 230 ns, 13.8 us per copy.
  Scene touching = s;
  touching.world.contacts = true;
  CHECK(nominal_ns_per_body_step("ours", true) == 230.0);
  CHECK(replicas_for(touching, 1.0 / 60, "ours", o) == 1);
  // The same answer however often it is asked, unlike a search timed on the machine.
  const TimingOptions d;
  CHECK(replicas_for(s, 1.0 / 60, "ours", d) == replicas_for(s, 1.0 / 60, "ours", d));
  CHECK(replicas_for(s, 1.0 / 60, "ours", d) == 256);  // 50 us: 128 last 26.9 us, 256 53.8 us
}

TEST_CASE("a cheap engine's timed sample repeats the run by a count fixed in code, not measured",
          "[timing]") {
  const Scene s = timing_scene();  // 2 dynamic bodies; 1/60: 30 steps, 60 body-steps per copy
  TimingOptions o;
  o.min_sample_seconds = 1e-5;
  CHECK(nominal_ns_per_body_step("ours") == 3.5);
  CHECK(nominal_ns_per_body_step("ours-f64") == 3.5);
  CHECK(nominal_ns_per_body_step("exec:python3 engine.py") == 1000.0);  // not listed
  // ours: 60 * 3.5 ns = 210 ns per run; 32 runs hold 6.7 us < 10 us, 64 hold 13.4 us.
  CHECK(repeats_for(s, 1.0 / 60, "ours", 1, o) == 64);
  // Replicas count: 4 copies are 840 ns per run; 8 runs hold 6.7 us, 16 hold 13.4 us.
  CHECK(repeats_for(s, 1.0 / 60, "ours", 4, o) == 16);
  // bullet: 60 * 580 ns = 34.8 us per run already exceeds 10 us.
  CHECK(repeats_for(s, 1.0 / 60, "bullet", 1, o) == 1);
  CHECK(repeats_for(s, 1.0 / 60, "exec:python3 engine.py", 1, o) == 1);
  o.max_repeats = 8;
  CHECK(repeats_for(s, 1.0 / 60, "ours", 1, o) == 8);
  // The defaults: a 2 ms sample. At ours's 256 copies x 60 body-steps x 3.5 ns = 54 us per run,
  // 32 runs hold 1.72 ms < 2 ms, 64 hold 3.4 ms.
  const TimingOptions d;
  CHECK(repeats_for(s, 1.0 / 60, "ours", replicas_for(s, 1.0 / 60, "ours", d), d) == 64);
  // mujoco: 2 copies x 60 body-steps x 550 ns = 66 us per run; 16 runs hold 1.06 ms, 32 hold 2.1.
  CHECK(replicas_for(s, 1.0 / 60, "mujoco", d) == 2);
  CHECK(repeats_for(s, 1.0 / 60, "mujoco", replicas_for(s, 1.0 / 60, "mujoco", d), d) == 32);
}

TEST_CASE("an engine whose sample is long at its nominal cost is timed in fewer rounds, unwarmed",
          "[timing]") {
  Scene s = timing_scene();
  s.duration = 200.0;  // 1/60: 12000 steps x 2 bodies = 24000 body-steps per copy
  TimingOptions o;
  o.samples = 5;
  // An unlisted engine at 1000 ns: one copy, one run of 24 ms, over the 10 ms of a long sample.
  const TimingPlan slow = timing_plan(s, 1.0 / 60, "exec:./slow", o);
  CHECK(slow.samples == o.long_samples);
  CHECK_FALSE(slow.warmed);
  CHECK(slow.replicas == 1);
  CHECK(slow.repeats == 1);
  // ours at 3.5 ns: 84 us per copy, one copy and 32 runs: 2.7 ms.
  const TimingPlan ours = timing_plan(s, 1.0 / 60, "ours", o);
  CHECK(ours.samples == 5);
  CHECK(ours.warmed);
  CHECK(ours.repeats == 32);
  o.samples = 2;  // never more rounds than asked for
  CHECK(timing_plan(s, 1.0 / 60, "exec:./slow", o).samples == 2);
  o.samples = 5;
  o.min_sample_seconds = 0.0;
  o.min_run_seconds = 0.0;
  std::string made;
  const auto engine = [&made](char tag) { return tagged_ours(made, tag); };
  // Named as a slow external engine, so planned as one; it runs ours.
  const std::vector<Timing> t =
      time_engines({{"ours", engine('o')}, {"exec:./slow", engine('x')}}, s, 1.0 / 60, o);
  REQUIRE(t.size() == 2);
  CHECK(t[0].samples() == 5);
  CHECK(t[1].samples() == 3);
  CHECK(t[1].calibration.size() == 3);  // the rounds it ran
  CHECK(std::equal(t[1].calibration.begin(), t[1].calibration.end(), t[0].calibration.begin()));
  // The warm-up round makes ours only; the long one runs in the first three timed rounds.
  CHECK(made ==
        "o"
        "ox"
        "xo"
        "ox"
        "o"
        "o");
}

TEST_CASE("a timing with repeats reports per copy and per run, and says how many it summed",
          "[timing]") {
  const Scene s = timing_scene();
  TimingOptions o;
  o.min_run_seconds = 0.0;
  o.min_sample_seconds = 1e-5;  // ours: 64 repeats of 210 ns (above)
  o.warmups = 0;
  o.samples = 4;
  const std::vector<Timing> t =
      time_engines({{"ours", [] { return make_engine("ours"); }}}, s, 1.0 / 60, o);
  REQUIRE(t.size() == 1);
  CHECK(t[0].replicas == 1);
  CHECK(t[0].repeats == 64);
  CHECK(t[0].samples() == 4);
  CHECK(t[0].of(Statistic::median) > 0.0);
  // Per simulated second of one copy: the 64 runs are 32 simulated seconds; the sum of their
  // stepping loops cannot take less than 0 or (here) anywhere near 1 s per simulated second.
  CHECK(t[0].of(Statistic::median) < 1.0);
}

TEST_CASE("a timing's statistics are order statistics of its samples", "[timing]") {
  Timing t;
  t.full = {4.0, 1.0, 3.0, 2.0, 5.0};
  t.bare = {1.0, 1.0, 2.0, 2.0, 2.0};
  t.calibration = {0.5, 0.25, 1.0, 1.0, 1.0};
  CHECK(t.headline() == 1.0);  // kHeadline: the minimum
  CHECK(t.of(Statistic::q25) == 2.0);
  CHECK(t.of(Statistic::median) == 3.0);
  CHECK(t.ratio() == 4.0);                   // 1.0 / 0.25
  CHECK(t.ratio(Statistic::median) == 3.0);  // 3.0 / 1.0
  CHECK(t.overhead() == Approx(0.5));        // medians 3.0 / 2.0 - 1
  CHECK(statistic({}, Statistic::median) == 0.0);
  CHECK(quantile({1.0, 2.0}, 0.75) == 1.75);
  CHECK(Timing{}.ratio() == 0.0);
}

TEST_CASE("timing runs every engine once a round, alternating from round to round", "[timing]") {
  const Scene s = timing_scene();
  TimingOptions o;
  o.min_run_seconds = 0.0;
  o.min_sample_seconds = 0.0;
  o.warmups = 1;
  o.samples = 4;
  std::string order;  // one letter per engine made: one per engine and round
  const auto engine = [&order](char tag) { return tagged_ours(order, tag); };
  const std::vector<Timing> t =
      time_engines({{"ours", engine('b')}, {"ours-again", engine('c')}}, s, 1.0 / 120, o);
  // Five rounds back to back; engines alternate, the warm-up round (-1) backward.
  CHECK(order ==
        "cb"
        "bc"
        "cb"
        "bc"
        "cb");
  REQUIRE(t.size() == 2);
  CHECK(t[0].engine == "ours");
  CHECK(t[1].engine == "ours-again");
  for (const Timing& one : t) {
    CHECK(one.h == 1.0 / 120);
    CHECK(one.samples() == 4);
  }
}

TEST_CASE("the statistics and the side-by-side ratio of hand-made samples", "[timing]") {
  Timing t;
  t.full = {5.0, 3.0, 4.0, 2.0, 6.0};  // round order, not sorted
  t.calibration = {1.0, 0.5, 2.0, 0.5, 1.0};
  t.bare = {1.0, 1.0, 1.0, 1.0, 1.0};
  CHECK(t.headline() == 2.0);                 // the minimum
  CHECK(t.of(Statistic::q25) == 3.0);         // sorted 2 3 4 5 6: position 1
  CHECK(t.of(Statistic::median) == 4.0);      // position 2
  CHECK(t.ratio() == 4.0);                    // min / min of the calibration: 2 / 0.5
  CHECK(t.ratio(Statistic::median) == 4.0);   // 4 / 1
  CHECK(t.overhead() == Approx(3.0));         // median / bare median - 1
  CHECK(quantile({1.0, 2.0}, 0.25) == 1.25);  // linear between order statistics
  CHECK(Timing{}.ratio() == 0.0);
}
