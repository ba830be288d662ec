// Tests ours/accumulator.hpp: the seed's fixed-timestep loop with a cap on steps per frame.
//
// Invariant of the accumulator (exact arithmetic): after frames d_1..d_k with no cap reached,
//   steps = floor(sum d / h) and carried = sum d - steps*h in [0, h); alpha = carried / h.
// With the cap, the whole steps beyond MAX_STEPS_PER_FRAME go to droppedTime instead.
#include "ours/accumulator.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

TEST_CASE("steady frames of exactly 1/60 s run one step each in float and double",
          "[ours][accumulator]") {
  // Each frame adds exactly h to an accumulator of 0 and subtracts it again: no drift possible
  // as long as the frame time is the same float as the step (1.0f/60.0f, not 0.016667f).
  ours::PhysicsAccumulator<float> f;
  ours::PhysicsAccumulator<double> d;
  for (int frame = 0; frame < 100000; ++frame) {
    const auto sf = f.Advance(1.0f / 60.0f);
    const auto sd = d.Advance(1.0 / 60.0);
    REQUIRE(sf.steps == 1);
    REQUIRE(sd.steps == 1);
    REQUIRE(sf.alpha == 0.0f);
    REQUIRE(sd.alpha == 0.0);
  }
}

TEST_CASE("frames of half a step alternate zero and one step with alpha 0.5",
          "[ours][accumulator]") {
  // fl(1/120) = fl(1/60)/2 exactly (a power-of-two scaling), so two halves make one step exactly.
  ours::PhysicsAccumulator<float> a;
  for (int frame = 0; frame < 1000; ++frame) {
    const auto s = a.Advance(1.0f / 120.0f);
    REQUIRE(s.steps == frame % 2);
    REQUIRE(s.alpha == (frame % 2 ? 0.0f : 0.5f));
  }
}

TEST_CASE("jittery frames run floor(total time / step) steps and carry the remainder",
          "[ours][accumulator]") {
  // h = 1/64 and frame times in multiples of 2^-12 s are exact in double: the invariant holds
  // exactly, with no rounding to excuse.
  ours::PhysicsAccumulator<double> a;
  a.timestep = 1.0 / 64.0;
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> ticks(1, 200);  // 0.24 ms .. 49 ms: never 8 steps in a frame
  double total = 0.0;
  long long steps = 0;
  int idle_frames = 0, multi_frames = 0;
  for (int frame = 0; frame < 20000; ++frame) {
    const double dt = ticks(rng) / 4096.0;
    total += dt;
    const auto s = a.Advance(dt);
    steps += s.steps;
    idle_frames += s.steps == 0;
    multi_frames += s.steps > 1;
    REQUIRE(s.droppedTime == 0.0);
    REQUIRE(steps == static_cast<long long>(std::floor(total / a.timestep)));
    REQUIRE(a.physicsAccumulator == total - steps * a.timestep);
    REQUIRE(s.alpha == a.physicsAccumulator / a.timestep);
  }
  CHECK(idle_frames > 0);   // the jitter really produced frames with no step
  CHECK(multi_frames > 0);  // and frames with several
}

TEST_CASE("jittery frames around 1/60 s keep the step count to rounding of the total",
          "[ours][accumulator]") {
  // With h = 1/60 the running sums round; the count may differ from floor(total/h) only when
  // total/h is within rounding of a whole number, which this seed never hits.
  ours::PhysicsAccumulator<double> a;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(0.005, 0.03);
  double total = 0.0;
  long long steps = 0;
  for (int frame = 0; frame < 100000; ++frame) {
    const double dt = jitter(rng);
    total += dt;
    steps += a.Advance(dt).steps;
  }
  CHECK(steps == static_cast<long long>(std::floor(total / a.timestep)));
  CHECK(a.physicsAccumulator ==
        Approx(total - steps * a.timestep).margin(1e-9));  // measured 5.1e-12
}

TEST_CASE("a long frame runs several steps in one call", "[ours][accumulator]") {
  ours::PhysicsAccumulator<double> a;
  a.timestep = 0.25;
  const auto s = a.Advance(1.125);  // 4.5 steps, under the cap of 8
  CHECK(s.steps == 4);
  CHECK(s.droppedTime == 0.0);
  CHECK(s.alpha == 0.5);
  CHECK(a.Advance(0.125).steps == 1);  // the carried half step completes with the next half
}

TEST_CASE("a hitch of 0.5 s is capped at MAX_STEPS_PER_FRAME and the rest is reported dropped",
          "[ours][accumulator]") {
  REQUIRE(ours::MAX_STEPS_PER_FRAME == 8);
  ours::PhysicsAccumulator<double> a;
  a.timestep = 1.0 / 64.0;  // exact: 0.5 s is 32 steps
  const auto s = a.Advance(0.5);
  CHECK(s.steps == 8);
  CHECK(s.droppedTime == 24.0 / 64.0);  // 32 - 8 steps, not run silently
  CHECK(s.alpha == 0.0);
  const auto next = a.Advance(1.0 / 64.0);  // the next normal frame is normal again
  CHECK(next.steps == 1);
  CHECK(next.droppedTime == 0.0);
}

TEST_CASE("a hitch at the seed's 1/60 s step accounts for every second as run, dropped or carried",
          "[ours][accumulator]") {
  for (double hitch : {0.5, 0.2, 1.0, 10.0, 3600.0}) {
    ours::PhysicsAccumulator<double> d;
    const auto s = d.Advance(hitch);
    INFO("hitch " << hitch);
    CHECK(s.steps == 8);
    CHECK(s.droppedTime > 0.0);
    CHECK(s.alpha >= 0.0);
    CHECK(s.alpha < 1.0);
    // 8 steps + dropped + carried = the frame, to rounding of the 8 subtractions.
    CHECK(8 * d.timestep + s.droppedTime + d.physicsAccumulator ==
          Approx(hitch).epsilon(1e-12));  // measured 7.1e-16 relative
  }
}

TEST_CASE("a hitch longer than INT_MAX steps still leaves alpha at least 0 and below 1",
          "[ours][accumulator]") {
  // 1e9 s is 6e10 steps of 1/60: a whole-step count that does not fit in an int.
  ours::PhysicsAccumulator<double> d;
  const auto s = d.Advance(1e9);
  CHECK(s.steps == 8);
  CHECK(s.droppedTime ==
        Approx(1e9 - 8.0 / 60.0).margin(1e-6));  // measured 0 (ulp of 1e9 is 1.2e-7)
  CHECK(s.alpha >= 0.0);
  CHECK(s.alpha < 1.0);
  ours::PhysicsAccumulator<float> f;
  const auto sf = f.Advance(1e9f);
  CHECK(sf.steps == 8);
  CHECK(sf.droppedTime > 0.0f);
  CHECK(sf.alpha >= 0.0f);
  CHECK(sf.alpha < 1.0f);
}

TEST_CASE("alpha stays at least 0 and below 1 for every frame length from 1 us to 2 s",
          "[ours][accumulator]") {
  int checked = 0;
  for (int us = 1; us <= 2000000; us += 97) {
    ours::PhysicsAccumulator<float> f;
    ours::PhysicsAccumulator<double> d;
    const auto sf = f.Advance(us * 1e-6f);
    const auto sd = d.Advance(us * 1e-6);
    REQUIRE(sf.alpha >= 0.0f);
    REQUIRE(sf.alpha < 1.0f);
    REQUIRE(sd.alpha >= 0.0);
    REQUIRE(sd.alpha < 1.0);
    REQUIRE(sd.steps == std::min(ours::MAX_STEPS_PER_FRAME, int(us * 1e-6 / d.timestep + 1e-9)));
    ++checked;
  }
  CHECK(checked == 20619);
}
