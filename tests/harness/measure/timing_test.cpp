// Tests harness/measure/timing.cpp: replication keeps the physics of every copy, and timing returns
// figures. No timing thresholds: wall times depend on the machine and its load, and such tests
// flake.
#include "harness/measure/timing.hpp"

#include <catch2/catch.hpp>
#include <variant>

#include "harness/core/registry.hpp"
#include "harness/core/runner.hpp"

using namespace dropcheck;

namespace {

// A floor, a cube pushed by a constant force and a cube on a spring, all in the x-y plane.
Scene scene() {
  Scene s;
  s.name = "timing";
  s.duration = 0.5;
  s.world.gravity = {0.0, -9.8, 0.0};
  s.world.damping_rate = 0.5;
  Body floor, pushed, sprung;
  floor.name = "floor";
  floor.half_extents = {5.0, 0.5, 5.0};
  floor.position = {0.0, -0.5, 0.0};
  floor.is_static = true;
  pushed.name = "pushed";
  pushed.position = {-2.0, 6.0, 0.0};
  sprung.name = "sprung";
  sprung.position = {2.0, 4.0, 0.0};
  sprung.velocity = {0.5, 1.0, 0.0};
  s.bodies = {floor, pushed, sprung};
  s.forces.push_back({{1}, ConstantForce{{2.0, 0.0, 0.0}}});
  s.forces.push_back({{2}, Spring{{2.0, 5.0, 0.0}, 40.0, 0.3, 0.0}});
  return s;
}

}  // namespace

TEST_CASE("timing replicates every body and force, shifted along x", "[timing]") {
  const Scene s = scene();
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
}

TEST_CASE("every copy of a scene replicated for timing moves like the original", "[timing]") {
  const Scene s = scene();
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
  const Scene s = scene();
  TimingOptions fast;  // as little work as possible: this checks the plumbing, not the machine
  fast.min_run_seconds = 1e-5;
  fast.warmups = 0;
  fast.repeats = 2;
  fast.max_replicas = 2;
  const std::vector<std::pair<std::string, EngineFactory>> engines{
      {"ours", [] { return make_engine("ours"); }},
      {"ours-f64", [] { return make_engine("ours-f64"); }}};
  const std::vector<Timing> t = time_engines(engines, s, 1.0 / 60, fast);
  REQUIRE(t.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(t[i].engine == engines[i].first);
    CHECK(t[i].h == 1.0 / 60);
    CHECK(t[i].replicas >= 1);
    CHECK(t[i].replicas <= 2);
    CHECK(t[i].min_per_sim_s > 0.0);
    CHECK(t[i].median_per_sim_s >= t[i].min_per_sim_s);
    CHECK(t[i].bare_min_per_sim_s > 0.0);
  }
}
