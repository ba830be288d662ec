// Tests harness/judge/turned_verdict.cpp: ours and ours-f64 follow their turned-box contact law at
// every step of tumbling landings (with and without friction and restitution, and an edge landing
// while sliding); a run nudged at one step departs there, naming the quantity; an engine that
// declares no such law is not judged.
#include "harness/judge/turned_verdict.hpp"

#include <catch2/catch.hpp>
#include <utility>

#include "harness/core/registry.hpp"
#include "harness/core/timestep.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"

using namespace dropcheck;
using Catch::Contains;

namespace {

// tumble_drop with the material (mu, e; unset when negative) at `timestep`.
Scene tumble(double mu, double e, const std::string& timestep) {
  Scene s = load_scene(std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/tumble_drop.toml");
  for (Body& b : s.bodies) {
    if (mu >= 0.0) b.friction = mu;
    if (e >= 0.0) b.restitution = e;
  }
  std::string why;
  s.timestep = *parse_timestep(timestep, why);
  return s;
}

TurnedVerdict judged(const std::string& engine, const Scene& scene) {
  std::unique_ptr<Engine> e = make_engine(engine);
  return judge_turned_contact(scene, e->info(), run_scene(*e, scene, scene.timestep.seconds));
}

}  // namespace

TEST_CASE("ours and ours-f64 follow their turned-box contact law through a tumbling landing",
          "[contact][turned]") {
  const std::pair<double, double> materials[] = {{-1, -1}, {0.5, -1}, {-1, 0.4}, {0.6, 0.2}};
  for (const auto& [mu, e] : materials)
    for (const char* h : {"1/30", "1/120"})
      for (const char* engine : {"ours", "ours-f64"}) {
        const TurnedVerdict v = judged(engine, tumble(mu, e, h));
        INFO(engine << " " << h << " mu " << mu << " e " << e << ": " << v.sentence());
        CHECK(v.follows());
        CHECK(v.contact_steps > 0);
      }
}

TEST_CASE("a run nudged at one step departs there, naming the quantity", "[contact][turned]") {
  const Scene scene = tumble(0.5, -1, "1/60");
  std::unique_ptr<Engine> e = make_engine("ours-f64");
  Trajectory run = run_scene(*e, scene, scene.timestep.seconds);
  run.rotations[50 * run.bodies() + 1].angular_velocity.x() += 1e-9;
  const TurnedVerdict v = judge_turned_contact(scene, e->info(), run);
  CHECK_FALSE(v.follows());
  CHECK(v.first_departure == 50);
  CHECK(v.departure_quantity == "angular velocity");
  CHECK_THAT(v.sentence(), Contains("DEPARTS at step 50: angular velocity off"));
}

TEST_CASE("an engine that declares no turned-box contact law is not judged by it",
          "[contact][turned]") {
  const Scene scene = tumble(-1, -1, "1/60");
  EngineInfo info = make_engine("ours-f64")->info();
  info.turned_contact = TurnedContact::not_declared;
  const TurnedVerdict v = judge_turned_contact(scene, info, Trajectory{});
  CHECK_FALSE(v.follows());
  CHECK_THAT(v.not_judged, Contains("declares no turned-box contact law"));
}
