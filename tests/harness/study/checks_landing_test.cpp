// Tests the landing check of harness/study/checks.cpp with two engine doubles that follow the
// after-forces law exactly (v += (g + F/m)*h; v *= exp(-k*h); x += v*h): one stops each body on its
// floor wherever a step ends below it (an ideal inelastic contact that nothing jumps over, as
// continuous collision does), one has no floor at all (every step end is its only test, and it
// finds nothing). What each declares about continuous collision is a parameter.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "../test_dirs.hpp"
#include "harness/core/registry.hpp"
#include "harness/oracles/landing.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/checks.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;

namespace {

class FloorDouble final : public Engine {
 public:
  FloorDouble(bool stops, bool declares_ccd) : stops_(stops), declares_ccd_(declares_ccd) {}

  EngineInfo info() const override {
    EngineInfo i;
    i.name = stops_ ? "stops-on-floor" : "no-floor";
    i.capabilities.contacts = true;
    i.law = DampingOrder::AfterForces;
    i.continuous_collision = declares_ccd_;
    return i;  // rest_offset 0 +- 1e-3: an ideal floor rests exactly at the geometric height
  }
  void load(const Scene& scene, double h) override {
    scene_ = scene;
    h_ = h;
    phi_ = std::exp(-scene.world.damping_rate * h);
    state_.clear();
    for (const Body& b : scene.bodies) state_.push_back({b.position, b.velocity});
    forces_.assign(scene.bodies.size(), Vec3::Zero());
    rest_.assign(scene.bodies.size(), -INFINITY);
    for (const LandingSetup& s : landing_setups(scene)) rest_[s.body] = s.rest_height;
  }
  void set_forces(std::span<const Vec3> f) override { forces_.assign(f.begin(), f.end()); }
  void step() override {
    for (std::size_t i = 0; i < state_.size(); ++i) {
      const Body& b = scene_.bodies[i];
      if (b.is_static) continue;
      BodyState& s = state_[i];
      s.velocity = (s.velocity + (scene_.world.gravity + forces_[i] / b.mass) * h_) * phi_;
      s.position += s.velocity * h_;
      if (stops_ && s.position.y() < rest_[i]) {
        s.position.y() = rest_[i];
        s.velocity.y() = 0.0;
      }
    }
  }
  void read(std::span<BodyState> out) const override {
    std::copy(state_.begin(), state_.end(), out.begin());
  }

 private:
  bool stops_, declares_ccd_;
  Scene scene_;
  double h_ = 0.0, phi_ = 1.0;
  std::vector<BodyState> state_;
  std::vector<Vec3> forces_;
  std::vector<double> rest_;
};

// Which FloorDouble a check runs: one that stops bodies on their floor or one with no floor.
enum class Floor { none, stops };
// What that FloorDouble declares about continuous collision.
enum class Ccd { none, declared };

// The landing check of scenarios/<stem>.toml at the scene's own step, on that FloorDouble.
CheckResult landing_check(const std::string& stem, Floor floor, Ccd ccd) {
  const Scene scene = testing::shipped_scene(stem);
  const bool stops = floor == Floor::stops, declares_ccd = ccd == Ccd::declared;
  return check_landing(
      scene, [=] { return std::make_unique<FloorDouble>(stops, declares_ccd); }, scene.timestep);
}

}  // namespace

TEST_CASE("A body that tunnels as its law predicts, without continuous collision, is a LIMIT",
          "[checks][landing]") {
  const CheckResult r = landing_check("extreme/thin_floor", Floor::none, Ccd::none);
  INFO(r.message);
  CHECK(r.passed);
  CHECK(r.limit ==
        "tunnels: it travels 3.34 m per step at contact, more than the floor (0.01 m) plus its "
        "height (1 m); no continuous collision");
  CHECK_THAT(r.message, Contains("bullet: tunnelled through the floor as its own law predicts "
                                 "(step 1), final centre"));
}

TEST_CASE(
    "Tunnelling while declaring continuous collision, or falling through a floor the law would "
    "hit, FAILs with no limit",
    "[checks][landing]") {
  // Each row: what it is, the scene, what the engine double declares, what the message says.
  struct Case {
    std::string what, stem;
    Ccd ccd;
    std::string says;
  };
  const std::vector<Case> cases{
      {"declares continuous collision and tunnels", "extreme/thin_floor", Ccd::declared,
       "TUNNELLED although the engine declares continuous collision"},
      // At most 0.23 m per step onto a 1 m floor.
      {"no continuous collision, falls through a floor its law hits", "drop_on_floor", Ccd::none,
       "OUT OF RANGE"},
  };
  for (const Case& c : cases) {
    const CheckResult r = landing_check(c.stem, Floor::none, c.ccd);
    INFO(c.what << ": " << r.message);
    CHECK_FALSE(r.passed);
    CHECK(r.limit.empty());
    CHECK_THAT(r.message, Contains(c.says));
  }
}

TEST_CASE(
    "A run that ends less than the still window after first contact does not judge "
    "stillness",
    "[checks][landing]") {
  // thin_floor lasts 0.5 s; the cube is stopped at step 1, so the run ends 29/60 s later.
  const CheckResult r = landing_check("extreme/thin_floor", Floor::stops, Ccd::declared);
  INFO(r.message);
  CHECK(r.passed);
  CHECK(r.limit.empty());
  CHECK_THAT(r.message, Contains("first contact at step 1 (law: step 1;"));
  CHECK_THAT(r.message, Contains("stillness not judged: the run ends 0.483 s after first contact "
                                 "(window 2 s)"));
  CHECK_THAT(r.message, !Contains("NOT STILL"));
  // A run long enough is judged over its last 2 s.
  const CheckResult d = landing_check("drop_on_floor", Floor::stops, Ccd::none);
  INFO(d.message);
  CHECK(d.passed);
  CHECK_THAT(d.message, Contains("still: max |v| 0 m/s, range 0 m over the last 2 s"));
}

TEST_CASE("The landing check names the stacked bodies it does not judge, and why",
          "[checks][landing]") {
  const CheckResult r = landing_check("extreme/mass_ratio", Floor::stops, Ccd::none);
  INFO(r.message);
  CHECK(r.passed);
  CHECK(r.limit.empty());
  CHECK_THAT(r.message, Contains("'heavy_1e3' not judged: lands on dynamic body 'light_1e3' (the "
                                 "landing oracle covers one body over a static floor)"));
  CHECK_THAT(r.message, Contains("'light_1e5' not judged: dynamic body 'heavy_1e5' lands on it"));
  CHECK_THAT(r.message, Contains("no body is judged here: a stack, a slide or a bounce is judged "
                                 "by its own contact law"));
  CHECK_THAT(r.message, !Contains("first contact"));
}

// A turning body meets the floor with a corner or an edge: the flat-landing oracle does not apply.
// The check runs the engine (Bullet, a real one with contacts and rotation), says so, and judges
// only that the body ends above the floor; a body that fell through fails it.
TEST_CASE("a tumbling cube's landing is compared, not judged by the flat-landing oracle",
          "[check][landing][rotation]") {
  const std::string head = R"(
duration = 2.0
[world]
gravity = [0.0, -9.8, 0.0]
contacts = true
[[body]]
name = "floor"
static = true
half_extents = [10.0, 0.5, 10.0]
position = [0.0, -0.5, 0.0]
[[body]]
name = "cube"
angular_velocity = [2.0, 3.0, 1.0]
)";
  const Scene landing = parse_scene(head + "position = [0.0, 3.0, 0.0]\n", "tumble.toml");
  const CheckResult r = check_landing(
      landing, [] { return make_engine("bullet"); }, landing.timestep);
  CHECK(r.passed);
  CHECK_THAT(r.message, Contains("a turning body's landing has no closed form") &&
                            Contains("cube ends at y = 0.49"));
  // Thrown down at 2000 m/s (33 m per step at 1/60), it jumps over the 1 m floor between two step
  // ends (Bullet tests overlap at step ends only) and ends under it: named as falling through.
  const Scene under = parse_scene(
      head + "position = [0.0, 3.0, 0.0]\nvelocity = [0.0, -2000.0, 0.0]\n", "fast.toml");
  const CheckResult u = check_landing(
      under, [] { return make_engine("bullet"); }, under.timestep);
  INFO(u.message);
  CHECK_FALSE(u.passed);
  CHECK_THAT(u.message, Contains("BELOW the floor's top"));
}

// Under gravity with a part along the floor, a body that lands slides on: no landing closed form
// holds, so what is judged is that every body ends above its floor (ODE, a real engine).
TEST_CASE("a landing under tilted gravity is judged only by the floor", "[checks][landing]") {
  if (!make_engine("ode")) return;
  Scene scene = load_scene(std::string(DROPCHECK_SOURCE_DIR) + "/scenarios/incline_slide.toml");
  scene.bodies[0].friction.reset();    // no material: not a slide, a body on an incline
  scene.bodies[0].position.y() = 1.5;  // dropped 1 m
  const std::vector<CheckResult> checks = check_scene(
      scene, [] { return make_engine("ode"); }, [] { return make_engine("ode"); });
  REQUIRE(checks.size() == 1);
  INFO(checks[0].message);
  CHECK(checks[0].passed);
  CHECK_THAT(checks[0].message,
             Contains("gravity has a part along the floor") && Contains("cube ends at y = "));
}
