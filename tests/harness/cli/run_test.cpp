// Tests harness/cli/cmd_run.cpp through dropcheck::cli_main: exit codes, messages on err, and the
// CSV/JSON files `run` writes (whole, exact, deterministic, absent after a failure).
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../test_dirs.hpp"
#include "cli_driver.hpp"
#include "harness/cli/cli.hpp"
#include "harness/core/registry.hpp"
#include "harness/run/runner.hpp"
#include "harness/scene/scene_loader.hpp"
#include "tests/scene_texts.hpp"

using Catch::Matchers::Contains;
namespace fs = std::filesystem;
using dropcheck::testing::ScratchDir;
using dropcheck::testing::slurp;

namespace {

const std::string kWind = DROPCHECK_SOURCE_DIR "/scenarios/wind.toml";  // 2 bodies, a force, 2 s
const std::string kThrowUp = DROPCHECK_SOURCE_DIR "/scenarios/throw_up.toml";  // v0 != 0, 2 s

using dropcheck::testing::cli;
using dropcheck::testing::Result;

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, sep);) out.push_back(item);
  return out;
}

bool cli_same_bits(const std::string& text, double v) {
  const double r = std::strtod(text.c_str(), nullptr);
  return std::memcmp(&r, &v, sizeof r) == 0;
}

}  // namespace

TEST_CASE("run on a missing file exits 2 naming the file on err", "[cli]") {
  const Result r = cli({"run", "no/such/scene.toml"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("no/such/scene.toml") && Contains("cannot read"));
  CHECK(r.out.empty());
}

TEST_CASE("run on a malformed file exits 2 with the loader's file, key and problem on err",
          "[cli]") {
  ScratchDir dir("malformed");
  std::ofstream(dir.file("bad.toml"))
      << "duration = 1.0\n[world]\ngravity = [0, -9.8, 0]\n"
         "[[body]]\nname = \"cube\"\nposition = [0, 0, 0]\nmass = 0.0\n";
  const Result r = cli({"run", dir.file("bad.toml")});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("bad.toml:7: body[0].mass: must be > 0 kg"));
}

TEST_CASE("run --engine nope exits 2 naming the engine", "[cli]") {
  const Result r = cli({"run", kWind, "--engine", "nope"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("nope") && Contains("unknown engine"));
}

TEST_CASE("run --dt 0.7 on a 2 s scene exits 2: not a whole number of steps", "[cli]") {
  const Result r = cli({"run", kThrowUp, "--dt", "0.7"});
  CHECK(r.code == 2);
  CHECK_THAT(r.err, Contains("--dt 0.7") && Contains("not a whole number of steps"));
  CHECK(cli({"run", kThrowUp, "--dt", "abc"}).code == 2);
  CHECK(cli({"run", kThrowUp, "--dt", "1/0"}).code == 2);
}

TEST_CASE("run with a bad usage exits 2: no file, two files, an unknown option, a missing value",
          "[cli]") {
  CHECK(cli({"run"}).code == 2);
  CHECK(cli({"run", kWind, kThrowUp}).code == 2);
  const Result unknown = cli({"run", kWind, "--bogus"});
  CHECK(unknown.code == 2);
  CHECK_THAT(unknown.err, Contains("--bogus") && Contains("unknown option"));
  const Result missing = cli({"run", kWind, "--csv"});
  CHECK(missing.code == 2);
  CHECK_THAT(missing.err, Contains("--csv") && Contains("expects a value"));
}

TEST_CASE("a failing run leaves no output file and no temporary behind", "[cli]") {
  ScratchDir dir("fail");
  const Result r = cli({"run", kThrowUp, "--dt", "0.7", "--csv", dir.file("out.csv"), "--json",
                        dir.file("out.json")});
  CHECK(r.code == 2);
  CHECK(fs::is_empty(dir.path));
}

TEST_CASE(
    "run --csv writes the contract's header, step 0 first and numbers equal to run_scene bit for "
    "bit",
    "[cli]") {
  ScratchDir dir("csv");
  const Result r =
      cli({"run", kWind, "--engine", "ours", "--engine", "ours-f64", "--csv", dir.file("out.csv")});
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Contains("ours ") && Contains("ours-f64 "));
  const std::vector<std::string> lines = split(slurp(dir.file("out.csv")), '\n');
  REQUIRE(!lines.empty());
  CHECK(lines[0] == "engine,dt,step,t,body,x,y,z,vx,vy,vz");

  const dropcheck::Scene scene = dropcheck::load_scene(kWind);
  std::size_t row = 1;
  for (const char* name : {"ours", "ours-f64"}) {
    auto engine = dropcheck::make_engine(name);
    const dropcheck::Trajectory t = dropcheck::run_scene(*engine, scene, scene.timestep.seconds);
    REQUIRE(t.samples() == 121);  // every step of 2 s at 1/60, and step 0
    for (std::size_t s = 0; s < t.samples(); ++s) {
      for (std::size_t b = 0; b < t.bodies(); ++b, ++row) {
        REQUIRE(row < lines.size());
        const std::vector<std::string> f = split(lines[row], ',');
        REQUIRE(f.size() == 11);
        INFO(lines[row]);
        CHECK(f[0] == name);
        CHECK(cli_same_bits(f[1], 1.0 / 60.0));
        CHECK(f[2] == std::to_string(t.recorded[s]));
        CHECK(cli_same_bits(f[3], t.time(s)));
        CHECK(f[4] == t.body_names[b]);
        for (int k = 0; k < 3; ++k) {
          CHECK(cli_same_bits(f[5 + k], t.at(s, b).position[k]));
          CHECK(cli_same_bits(f[8 + k], t.at(s, b).velocity[k]));
        }
      }
    }
  }
  CHECK(row == lines.size());
  // Step 0 is the scene's initial state: "medium" at (-2, 6, 0) at rest.
  CHECK(lines[1] == "ours,0.016666666666666666,0,0,medium,-2,6,0,0,0,0");
}

TEST_CASE("run --dt 1/120 runs and records at that step", "[cli]") {
  ScratchDir dir("dt");
  REQUIRE(
      cli({"run", kThrowUp, "--engine", "ours-f64", "--dt", "1/120", "--csv", dir.file("out.csv")})
          .code == 0);
  const std::vector<std::string> lines = split(slurp(dir.file("out.csv")), '\n');
  REQUIRE(lines.size() == 1 + 241);  // 2 s at 1/120, one body, step 0 included
  CHECK(lines.back().rfind("ours-f64,0.0083333333333333332,240,2,cube,", 0) == 0);
}

TEST_CASE("running the same scene twice gives byte-identical CSV and JSON", "[cli][determinism]") {
  ScratchDir dir("determinism");
  for (const char* n : {"1", "2"})
    REQUIRE(cli({"run", kWind, "--engine", "ours", "--engine", "ours-f64", "--csv",
                 dir.file(std::string(n) + ".csv"), "--json", dir.file(std::string(n) + ".json")})
                .code == 0);
  const std::string csv = slurp(dir.file("1.csv"));
  CHECK(csv.size() > 10000);  // 2 engines x 121 samples x 2 bodies
  CHECK(csv == slurp(dir.file("2.csv")));
  CHECK(slurp(dir.file("1.json")) == slurp(dir.file("2.json")));
}

TEST_CASE(
    "run --csv on a rotating scene adds qw..wz: a cube spun about z turns by 2*atan(h*w/2) "
    "per step under ours's first-order update",
    "[cli][rotation]") {
  ScratchDir d("run-rotation");
  const std::string scene =
      d.write("spin.toml",
              "duration = 0.5\n[world]\ngravity = [0.0, -9.8, 0.0]\n[[body]]\nname = "
              "\"c\"\nposition = [0.0, 10.0, 0.0]\nangular_velocity = [0.0, 0.0, 1.0]\n");
  const Result r = cli({"run", scene, "--engine", "ours-f64", "--csv", d.file("spin.csv")});
  REQUIRE(r.code == 0);
  const std::vector<std::string> lines = split(slurp(d.file("spin.csv")), '\n');
  REQUIRE(lines.size() == 1 + 31);
  CHECK(lines[0] == "engine,dt,step,t,body,x,y,z,vx,vy,vz,qw,qx,qy,qz,wx,wy,wz");
  CHECK(lines[1] == "ours-f64,0.016666666666666666,0,0,c,0,10,0,0,0,0,1,0,0,0,0,0,1");
  // q + (h/2)*(0, w)*q, normalised, turns by 2*atan(h*w/2) about w; w stays 1 exactly (a
  // principal axis: w x I*w = 0).
  const std::vector<std::string> last = split(lines.back(), ',');
  REQUIRE(last.size() == 18);
  const double turned = 30 * 2.0 * std::atan(0.5 / 60.0);
  CHECK(std::stod(last[11]) == Approx(std::cos(turned / 2)).margin(1e-14));
  CHECK(std::stod(last[14]) == Approx(std::sin(turned / 2)).margin(1e-14));
  CHECK(last[17] == "1");
}

TEST_CASE("a rotating scene is skipped, with the reason, by an engine that cannot turn it",
          "[cli][rotation]") {
  ScratchDir d("run-rotation-skip");
  const std::string scene =
      d.write("tilt.toml",
              "duration = 0.5\n[world]\ngravity = [0.0, -9.8, 0.0]\n[[body]]\nname = "
              "\"c\"\nposition = [0.0, 10.0, 0.0]\nangular_velocity = [1.0, 0.0, 0.0]\n");
  const Result r = cli({"run", scene, "--engine", "box2d"});
  CHECK(r.code == 1);  // no engine ran it
  CHECK_THAT(r.out, Contains("box2d  skipped: rotation: a 2-D engine turns bodies about z only"));
  CHECK_THAT(r.err, Contains("no engine ran the scene to its end"));
}

TEST_CASE("identify --trajectory names the rotational member of a run read back from its CSV",
          "[cli][identify][rotation]") {
  ScratchDir d("identify-rotation");
  const std::string scene = DROPCHECK_SOURCE_DIR "/scenarios/gazebo_boxes_complex.toml";
  REQUIRE(cli({"run", scene, "--engine", "bullet", "--csv", d.file("bullet.csv")}).code == 0);
  const Result r = cli({"identify", scene, "--trajectory", d.file("bullet.csv")});
  // Exit 1: without damping the linear members tie (phi = 1), which identify reports as before.
  CHECK(r.code == 1);
  CHECK_THAT(r.out, Contains("ambiguous: ") && Contains("best fit: implicit-body/exp-map"));
  const Result e = cli({"identify", scene, "--engine", "mujoco"});
  CHECK_THAT(e.out, Contains("declared rotation explicit/exp-map: matches"));
}

TEST_CASE("identify on a bounce and a tumbling landing names the contact law member followed",
          "[cli][identify][contact]") {
  const Result b =
      cli({"identify", DROPCHECK_SOURCE_DIR "/scenarios/bounce_e01.toml", "--engine", "ode"});
  CHECK(b.code == 0);
  CHECK_THAT(b.out, Contains("identify bounce_e01: ode's bounce law from its run at h = ") &&
                        Contains("  follows  restitution of the step-start approach speed, "
                                 "push-out 0.2*depth/h capped at 0.3 m/s (declared by ode)") &&
                        Contains("  departs  ") && Contains(": matches"));
  const Result t =
      cli({"identify", DROPCHECK_SOURCE_DIR "/scenarios/tumble_drop.toml", "--engine", "ours-f64"});
  CHECK(t.code == 0);
  CHECK_THAT(t.out, Contains("  follows  one impulse at the mean of the corners in the floor "
                             "(declared by ours, ours-f64)") &&
                        Contains("declared one impulse at the mean of the corners in the floor: "
                                 "matches"));
  const Result n = cli({"identify", DROPCHECK_SOURCE_DIR "/scenarios/tumble_drop.toml"});
  CHECK(n.code == 2);
}

TEST_CASE("identify --trajectory reads a Gazebo benchmark log and names its rotational member",
          "[cli][identify][rotation]") {
  // Bullet's run of Gazebo's complex case, written back into Gazebo's frame and log format.
  ScratchDir d("identify-gazebo");
  const std::string scene = DROPCHECK_SOURCE_DIR "/scenarios/gazebo_boxes_complex.toml";
  REQUIRE(cli({"run", scene, "--engine", "bullet", "--csv", d.file("bullet.csv")}).code == 0);
  std::ofstream log(d.file("gazebo.csv"));
  log << "physics_engine,time_step,complex,collisiion,model_count,wall_time,log_multiple,"
         "classname\nbullet,0.001,1,0,1,0.6,1,Boxes\n"
         "sim_time,model_no,linear_velocity_x,linear_velocity_y,linear_velocity_z,"
         "angular_velocity_x,angular_velocity_y,angular_velocity_z,position_x,position_y,"
         "position_z,quaternion_w,quaternion_x,quaternion_y,quaternion_z\n";
  log.precision(17);
  const double r = std::sqrt(0.5);
  const std::vector<std::string> rows = split(slurp(d.file("bullet.csv")), '\n');
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const std::vector<std::string> f = split(rows[i], ',');
    const auto n = [&](int k) { return std::stod(f[static_cast<std::size_t>(k)]); };
    // (x, y, z) -> (x, -z, y) back to z-up; q -> m*q*m^-1 with m = (r, r, 0, 0).
    const double qw = n(11), qx = n(12), qy = n(13), qz = n(14);
    const double aw = r * qw - r * qx, ax = r * qx + r * qw, ay = r * qy - r * qz,
                 az = r * qz + r * qy;  // m*q
    const double gw = aw * r + ax * r, gx = ax * r - aw * r, gy = ay * r - az * r,
                 gz = az * r + ay * r;  // (m*q)*conj(m)
    log << n(3) + 0.001 << ",0," << n(8) << "," << -n(10) << "," << n(9) << "," << n(15) << ","
        << -n(17) << "," << n(16) << "," << n(5) << "," << -n(7) << "," << n(6) << "," << gw << ","
        << gx << "," << gy << "," << gz << "\n";
  }
  log.close();
  const Result id = cli({"identify", scene, "--trajectory", d.file("gazebo.csv")});
  CHECK_THAT(id.out, Contains("reading model_0 as body 'box'") &&
                         Contains("best fit: implicit-body/exp-map"));
}

TEST_CASE(
    "identify on a slide names the engine's friction model from its slides at 0 and 45 "
    "degrees",
    "[cli][identify][contact]") {
  const std::string scene = DROPCHECK_SOURCE_DIR "/scenarios/slide_stop.toml";
  // ODE (dContactApprox1): 2.509472 m straight, 1.762376 m at 45 degrees: ratio 0.70229.
  const Result r = cli({"identify", scene, "--engine", "ode"});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("ratio 0.70229") && Contains("): box pyramid;") &&
                        Contains("declared box pyramid: matches"));
  // A trajectory is one run: the ratio needs two.
  const Result t = cli({"identify", scene, "--trajectory", "x.csv"});
  CHECK(t.code == 2);
  CHECK_THAT(t.err, Contains("use --engine E"));
  // An engine without contacts is refused with its reason; a 2-D engine has one tangent direction.
  const Result c = cli({"identify", scene, "--engine", "wildmagic"});
  CHECK(c.code == 2);
  CHECK_THAT(c.err, Contains("contacts"));
  const Result b = cli({"identify", scene, "--engine", "box2d"});
  CHECK(b.code == 0);
  CHECK_THAT(b.out, Contains("friction model: not applicable: box2d is a 2-D engine"));
  // Its solver is named instead: its own iterations follow, a neighbour's depart.
  CHECK_THAT(b.out, Contains("box2d's contact solver from its run") &&
                        Contains("  follows  Box2D 2.4 sequential impulses (8 velocity") &&
                        Contains("  departs  Box2D 2.4 sequential impulses (32 velocity") &&
                        Contains(": matches"));
  // An incline: its pull turned to 45 degrees. ODE's box pyramid holds the cube there, as the cone
  // would; only a sum pyramid would let it slip.
  const Result i =
      cli({"identify", DROPCHECK_SOURCE_DIR "/scenarios/incline_hold.toml", "--engine", "ode"});
  CHECK(i.code == 0);
  CHECK_THAT(i.out, Contains("held at 0 degrees") &&
                        Contains("cone or box pyramid (this slide cannot tell them apart)") &&
                        Contains("declared box pyramid: consistent"));
}

TEST_CASE(
    "identify --combine names each engine's rule for two bodies' friction, and each engine's "
    "friction model",
    "[cli][identify][contact]") {
  const std::string scene = DROPCHECK_SOURCE_DIR "/scenarios/slide_stop.toml";
  // The cube 0.2 on a floor of 0.8, each passed verbatim: measured 0.16, 0.4 and 0.8.
  const Result bullet = cli({"identify", scene, "--engine", "bullet", "--combine"});
  CHECK(bullet.code == 0);
  CHECK_THAT(bullet.out, Contains("combine rule: mu 0.16 ") && Contains("0.8): product;"));
  // Its model, from the scene's slides at 0 and 45 degrees: ratio 1.0063 (its box rocks on its
  // manifold's corners), a cone, as its adapter declares.
  CHECK_THAT(bullet.out, Contains("): cone;") && Contains("declared cone: matches"));
  const Result box2d = cli({"identify", scene, "--engine", "box2d", "--combine"});
  CHECK_THAT(box2d.out, Contains("combine rule: mu 0.4 ") && Contains("): geometric mean;"));
  // MuJoCo's default pyramidal cone: the sum pyramid, ratio 1.421.
  const Result mujoco = cli({"identify", scene, "--engine", "mujoco", "--combine"});
  CHECK(mujoco.code == 0);
  CHECK_THAT(mujoco.out, Contains("combine rule: mu 0.8 ") && Contains("): maximum;") &&
                             Contains("ratio 1.421") && Contains("): sum pyramid;"));
  // ODE's near callback sets each pair: no rule to identify; its model as before.
  const Result ode = cli({"identify", scene, "--engine", "ode", "--combine"});
  CHECK(ode.code == 0);
  CHECK_THAT(ode.out, Contains("combine rule: not identified: ode's adapter sets each pair") &&
                          Contains("declared box pyramid: matches"));
  CHECK(cli({"identify", scene, "--trajectory", "x.csv", "--combine"}).code == 2);
}

TEST_CASE("check takes a folder for the scene files directly in it, in name order",
          "[cli][check]") {
  ScratchDir d("check-folder");
  std::filesystem::create_directories(d.file("set/deeper"));
  using dropcheck::testing::kEarth;
  const std::string scene =
      dropcheck::testing::scene_head("0.5", "1/60", kEarth) +
      dropcheck::testing::body_text("cube", "[0.0, 10.0, 0.0]", "[0.0, 0.0, 0.0]");
  std::ofstream(d.file("set/b.toml")) << "name = \"second\"\n" << scene;
  std::ofstream(d.file("set/a.toml")) << "name = \"first\"\n" << scene;
  std::ofstream(d.file("set/notes.txt")) << "not a scene";
  std::ofstream(d.file("set/deeper/c.toml")) << "name = \"not taken\"\n" << scene;
  const Result r = cli({"check", d.file("set"), "--engine", "ours-f64"});
  CHECK(r.code == 0);
  const std::size_t first = r.out.find("PASS  first"), second = r.out.find("PASS  second");
  CHECK(first != std::string::npos);
  CHECK(second != std::string::npos);
  CHECK(first < second);
  CHECK(r.out.find("not taken") == std::string::npos);
  std::filesystem::create_directories(d.file("empty"));
  const Result empty = cli({"check", d.file("empty"), "--engine", "ours-f64"});
  CHECK(empty.code == 2);
  CHECK_THAT(empty.err, Contains("empty") && Contains("a folder without a scene file"));
}

TEST_CASE("run's and engines' columns stay aligned whatever the length of a name", "[cli][run]") {
  ScratchDir d("aligned-columns");
  const std::string name(40, 'b');
  std::ofstream(d.file("s.toml")) << dropcheck::testing::scene_head("0.1", "1/60",
                                                                    dropcheck::testing::kEarth)
                                  << dropcheck::testing::body_text(name, "[0.0, 1.0, 0.0]",
                                                                   "[0.0, 0.0, 0.0]");
  const Result r = cli({"run", d.file("s.toml"), "--engine", "ours-f64", "--engine", "ours"});
  REQUIRE(r.code == 0);
  std::istringstream lines(r.out);
  std::string line, header;
  std::getline(lines, line);  // the scene line
  std::getline(lines, header);
  int rows = 0;
  while (std::getline(lines, line)) {
    INFO(header << "\n" << line);
    CHECK(line.find(" ok") + 1 == header.find("status"));
    ++rows;
  }
  CHECK(rows == 2);
  const Result e = cli({"engines"});
  std::istringstream table(e.out);
  std::getline(table, header);
  while (std::getline(table, line)) {
    if (line.find("  (") != std::string::npos) continue;  // not compiled in
    INFO(header << "\n" << line);
    const std::size_t scalar =
        line.find(" f64 ") != std::string::npos ? line.find(" f64 ") : line.find(" f32 ");
    CHECK(scalar + 1 == header.find("scalar"));
  }
}

TEST_CASE("a skipped external engine is named by its own name, not its file's path",
          "[cli][check]") {
  const Result r = cli({"check", DROPCHECK_SOURCE_DIR "/scenarios/drop_on_floor.toml", "--engine",
                        DROPCHECK_SOURCE_DIR "/examples/python/seed_engine.toml"});
  CHECK_THAT(r.out, Contains("skipped: drop_on_floor  seed-python: no contacts"));
  CHECK(r.out.find("seed_engine.toml") == std::string::npos);
}

TEST_CASE("check with one engine ends with that engine's page: passed, failed, skipped and why",
          "[cli]") {
  if (!make_engine("wildmagic")) return;
  const Result r =
      cli({"check", DROPCHECK_SOURCE_DIR "/scenarios/throw_up.toml",
           DROPCHECK_SOURCE_DIR "/scenarios/bounce_e01.toml", "--engine", "wildmagic"});
  CHECK(r.code == 0);
  CHECK_THAT(r.out, Contains("wildmagic alone: 2 scenes, 1 passed, 0 failed, 1 skipped") &&
                        Contains("  passed   throw_up (") &&
                        Contains("  skipped  bounce_e01: no contacts (declare the capability "
                                 "`contacts` to run it"));
  // Two engines: no page.
  const Result two = cli({"check", DROPCHECK_SOURCE_DIR "/scenarios/throw_up.toml", "--engine",
                          "wildmagic", "--engine", "ours"});
  CHECK_THAT(two.out, !Contains(" alone: "));
}
