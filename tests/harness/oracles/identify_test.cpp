// Tests harness/oracles/identify.cpp (and harness/io/trajectory_csv.cpp, its file input): every
// built-in engine's law is named from its own trajectory on wind.toml (damping, and a force that
// differs between bodies, so all five members separate); a non-Euler trajectory fits no member; a
// gravity-only scene is honestly ambiguous between after-forces and before-forces.
#include "harness/oracles/identify.hpp"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/cli/cli.hpp"
#include "harness/core/input_error.hpp"
#include "harness/core/registry.hpp"
#include "harness/io/trajectory_csv.hpp"
#include "harness/io/trajectory_io.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

Scene identify_scene(const std::string& name) {
  return load_scene(DROPCHECK_SOURCE_DIR "/scenarios/" + name + ".toml");
}

Trajectory run_identified(const std::string& engine, const Scene& s) {
  auto e = make_engine(engine);
  REQUIRE(e);
  return run_scene(*e, s, s.timestep.seconds);
}

std::string temp_file(const std::string& name, const std::string& text) {
  const fs::path p =
      fs::temp_directory_path() / ("dropcheck_identify_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(p) << text;
  return p.string();
}

// The engine's declared law is the one identified from its wind.toml trajectory, uniquely.
void require_identified(const std::string& engine) {
  if (!make_engine(engine)) {
    WARN(engine << ": " << engine_unavailable_reason(engine));
    return;
  }
  const Scene s = identify_scene("wind");
  const Identification id = identify_law(s, run_identified(engine, s));
  const MemberFit& best = id.fits[id.best];
  INFO(engine << ": best " << law_key(best.law) << " at " << best.max_dx << " m, runner-up "
              << law_key(id.fits[id.runner_up].law) << " at " << id.fits[id.runner_up].max_dx
              << " m");
  CHECK(best.law == make_engine(engine)->info().law);
  CHECK(id.fits_any);
  CHECK_FALSE(id.ambiguous);
  // Measured: residual 1.4e-13 m (f64 engines), 3.3e-6 m (f32: ours, box2d); runner-up >= 0.0144 m.
  CHECK(best.max_dx < 1e-5);
  CHECK(id.fits[id.runner_up].max_dx > 1e-2);
  CHECK(best.phi == Approx(0.98).epsilon(1e-6));  // wind.toml: linear_drag = 0.98 at h = 1/60
  CHECK(best.gravity.y() == Approx(-9.8).epsilon(1e-6));
}

}  // namespace

TEST_CASE("identify names the law of ours from its own trajectory", "[identify]") {
  require_identified("ours");
}
TEST_CASE("identify names the law of ours-f64 from its own trajectory", "[identify]") {
  require_identified("ours-f64");
}
TEST_CASE("identify names the law of bullet from its own trajectory", "[identify]") {
  require_identified("bullet");
}
TEST_CASE("identify names the law of ode from its own trajectory", "[identify]") {
  require_identified("ode");
}
TEST_CASE("identify names the law of box2d from its own trajectory", "[identify]") {
  require_identified("box2d");
}
TEST_CASE("identify names the law of mujoco from its own trajectory", "[identify]") {
  require_identified("mujoco");
}

TEST_CASE("A trajectory that is no fixed-step scheme of the family fits no member", "[identify]") {
  const Scene s = identify_scene("wind");
  Trajectory t = run_identified("ours-f64", s);
  for (std::size_t i = 0; i < t.states.size(); ++i)  // a 10 cm wobble no member can follow
    t.states[i].position.y() += 0.1 * std::sin(0.3 * static_cast<double>(i / t.bodies()));
  const Identification id = identify_law(s, t);
  CHECK_FALSE(id.fits_any);
  CHECK(id.fits[id.best].max_dx > kIdentifyTolerance);
  std::ostringstream out, err;
  const std::string csv = temp_file("wobble.csv", trajectories_to_csv(std::span(&t, 1)));
  CHECK(cli_main({"identify", s.source, "--trajectory", csv}, out, err) == kExitCheckFailed);
  CHECK_THAT(out.str(),
             Contains("no member fits better than 2 cm: not a fixed-step scheme of the family"));
}

TEST_CASE("A gravity-only scene cannot separate after-forces from before-forces with g fitted",
          "[identify]") {
  const Scene s = identify_scene("throw_up");
  const Identification id = identify_law(s, run_identified("ours-f64", s));
  CHECK(id.ambiguous);
  const Law pair[] = {id.fits[id.best].law, id.fits[id.runner_up].law};
  CHECK(
      ((pair[0] == Law{DampingOrder::AfterForces} && pair[1] == Law{DampingOrder::BeforeForces}) ||
       (pair[1] == Law{DampingOrder::AfterForces} && pair[0] == Law{DampingOrder::BeforeForces})));
  // ... but after-position (ODE) still separates there, by its positions.
  if (make_engine("ode")) {
    const Identification ode = identify_law(s, run_identified("ode", s));
    CHECK_FALSE(ode.ambiguous);
    CHECK(ode.fits[ode.best].law == Law{DampingOrder::AfterPosition});
  }
}

TEST_CASE("An undamped run fits phi = 1 on every member, RK4's included, without recursion",
          "[identify]") {
  // The RK4 member is refitted with the force share T(k*h) of its fitted phi; at phi = 1 exactly
  // (an f64 engine without damping) T = 1 again, which once recursed without end (SIGSEGV).
  const Scene s = identify_scene("free_fall");
  const Identification id = identify_law(s, run_identified("ours-f64", s));
  CHECK(id.determined);
  for (const MemberFit& m : id.fits) {
    INFO(law_key(m.law));
    CHECK(m.determined);
    CHECK(m.phi == Approx(1.0).margin(1e-12));
  }
  std::ostringstream out, err;
  CHECK(cli_main({"identify", s.source, "--engine", "ours-f64"}, out, err) == kExitCheckFailed);
  CHECK_THAT(out.str(), Contains("where the damping sits leaves no trace"));
}

TEST_CASE("A force-free run determines neither phi nor gravity, and every member ties",
          "[identify]") {
  // Gazebo's simple boxes: no gravity, a constant velocity. Any phi with c = (1 - phi)*v fits the
  // velocities, so the fit reports no figure (it once printed phi = 0.86 and g = 150 m/s^2).
  const Scene s = identify_scene("gazebo_boxes_simple");
  const Identification id = identify_law(s, run_identified("ours-f64", s));
  CHECK_FALSE(id.determined);
  CHECK(id.ambiguous);
  CHECK(id.tied.size() == id.fits.size());
  for (const MemberFit& m : id.fits) {
    CHECK_FALSE(m.determined);
    CHECK(m.max_dx < 1e-9);
  }
  std::ostringstream out, err;
  CHECK(cli_main({"identify", s.source, "--engine", "ours-f64"}, out, err) == kExitCheckFailed);
  CHECK_THAT(out.str(), Contains("not determined: the velocities do not change"));
  CHECK_THAT(out.str(), Contains("undetermined"));
  CHECK_THAT(out.str(), Contains("declared after-forces: one of the equal fits (not confirmed)"));
  // A changing velocity determines them again: the same box under gravity.
  Scene fall = s;
  fall.world.gravity = Vec3(0.0, -9.81, 0.0);
  const Identification g = identify_law(fall, run_identified("ours-f64", fall));
  CHECK(g.determined);
  CHECK(g.fits[0].gravity.y() == Approx(-9.81).epsilon(1e-9));
}

TEST_CASE("A trajectory CSV reads back exactly and identifies like the run it came from",
          "[identify]") {
  const Scene s = identify_scene("wind");
  const Trajectory t = run_identified("ours", s);
  const std::string csv = temp_file("ours.csv", trajectories_to_csv(std::span(&t, 1)));
  const std::vector<Trajectory> back = read_trajectories_csv(csv);
  REQUIRE(back.size() == 1);
  CHECK(back[0].engine == "ours");
  CHECK(back[0].h == t.h);
  CHECK(back[0].recorded == t.recorded);
  CHECK(back[0].body_names == t.body_names);
  for (std::size_t i = 0; i < t.states.size(); ++i) {
    REQUIRE(back[0].states[i].position == t.states[i].position);
    REQUIRE(back[0].states[i].velocity == t.states[i].velocity);
  }
  std::ostringstream out, err;
  CHECK(cli_main({"identify", s.source, "--trajectory", csv}, out, err) == kExitOk);
  CHECK_THAT(out.str(), Contains("best fit: after-forces (v = phi*(v + a*h); x += h*v)"));
}

TEST_CASE("identify rejects unusable input with the file and the problem", "[identify]") {
  const Scene s = identify_scene("wind");
  std::ostringstream out, err;
  const auto fails = [&](std::vector<std::string> argv, const std::string& message) {
    err.str("");
    CHECK(cli_main(argv, out, err) == kExitBadInput);
    CHECK_THAT(err.str(), Contains(message));
  };
  fails({"identify", s.source}, "expects exactly one of --engine E and --trajectory CSV");
  fails({"identify", s.source, "--engine", "ours", "--trajectory", "x.csv"},
        "expects exactly one of");
  const std::string header = "engine,dt,step,t,body,x,y,z,vx,vy,vz\n";
  fails({"identify", s.source, "--trajectory", temp_file("h.csv", "engine,dt\n")},
        ":1: the header must be");
  fails({"identify", s.source, "--trajectory",
         temp_file("n.csv", header + "ours,0.1,0,0,small,1,2,x,0,0,0\n")},
        ":2: z (column 8): 'x' is not a number");
  // No verdict from numbers that are not numbers: refused before any fit, line and column named.
  fails({"identify", s.source, "--trajectory",
         temp_file("nan.csv", header + "ours,0.1,0,0,small,1,2,3,0,0,0\n" +
                                  "ours,0.1,1,0.1,small,nan,2,3,0,0,0\n")},
        ":3: x (column 6): 'nan' is not a finite number");
  fails({"identify", s.source, "--trajectory",
         temp_file("inf.csv", header + "ours,inf,0,0,small,1,2,3,0,0,0\n")},
        ":2: dt (column 2): 'inf' is not a finite number");
  fails({"identify", s.source, "--trajectory",
         temp_file("b.csv",
                   header + "ours,0.1,0,0,small,1,2,3,0,0,0\nours,0.1,1,0.1,small,1,2,3,0,0,0\n")},
        "1 bodies, the scene has 2");
  const Trajectory a = run_identified("ours", s), b = run_identified("ours-f64", s);
  const Trajectory both[] = {a, b};
  fails({"identify", s.source, "--trajectory", temp_file("two.csv", trajectories_to_csv(both))},
        "holds 2 runs (ours at dt 0.0166667, ours-f64 at dt 0.0166667)");
  fails({"identify", DROPCHECK_SOURCE_DIR "/scenarios/drop_on_floor.toml", "--engine", "ours-f64"},
        "needs a free-flight scene (contacts = false)");
}
