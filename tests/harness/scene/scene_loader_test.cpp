// Tests harness/scene/scene_loader.cpp: valid scenes load with their defaults; every malformed
// scene is an InputError whose message names the file (and line), the key path and the problem.
#include "harness/scene/scene_loader.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

using Catch::Matchers::Contains;

namespace {

// A minimal valid scene; the malformed cases below change one thing in it.
const std::string kHead = "duration = 1.0\n";
const std::string kWorld = "[world]\ngravity = [0.0, -9.8, 0.0]\n";
const std::string kBody = "[[body]]\nname = \"cube\"\nposition = [0.0, 10.0, 0.0]\n";

std::string loader_scene(const std::string& head, const std::string& world,
                         const std::string& bodies, const std::string& tail = "") {
  return head + world + bodies + tail;
}

// The InputError message of parsing `text` as x.toml, or "(loaded)" when it loads.
std::string loader_error_of(const std::string& text) {
  try {
    dropcheck::parse_scene(text, "x.toml");
  } catch (const dropcheck::InputError& e) {
    return e.what();
  }
  return "(loaded)";
}

// Checks that the message names the file, the key and the problem.
void check_error(const std::string& text, const std::string& key, const std::string& problem) {
  const std::string msg = loader_error_of(text);
  INFO(text);
  CHECK_THAT(msg, Contains("x.toml:") && Contains(key + ": ") && Contains(problem));
}

}  // namespace

TEST_CASE("a minimal scene loads with the contract's defaults", "[loader]") {
  const dropcheck::Scene s =
      dropcheck::parse_scene(loader_scene(kHead, kWorld, kBody), "dir/minimal.toml");
  CHECK(s.name == "minimal");  // the file's stem
  CHECK(s.source == "dir/minimal.toml");
  CHECK(s.duration == 1.0);
  CHECK(s.timestep.seconds == 1.0 / 60.0);
  REQUIRE(s.timesteps.size() == 1);
  CHECK(s.timesteps[0].text == "1/60");
  CHECK(s.world.gravity == dropcheck::Vec3(0.0, -9.8, 0.0));
  CHECK(s.world.damping_rate == 0.0);
  CHECK_FALSE(s.world.contacts);
  REQUIRE(s.bodies.size() == 1);
  CHECK(s.bodies[0].half_extents == dropcheck::Vec3(0.5, 0.5, 0.5));
  CHECK(s.bodies[0].mass == 1.0);
  CHECK(s.bodies[0].velocity == dropcheck::Vec3::Zero());
  CHECK_FALSE(s.bodies[0].is_static);
  CHECK(s.forces.empty());
}

TEST_CASE("linear_drag 0.98 at 1/60 becomes k = -ln(0.98)*60 and decays by 0.98 per step",
          "[loader]") {
  const dropcheck::Scene s =
      dropcheck::parse_scene(loader_scene(kHead, kWorld + "linear_drag = 0.98\n", kBody), "x.toml");
  // k = -ln(f)/h, so exp(-k*h) = f at the scene's step.
  CHECK(s.world.damping_rate ==
        Approx(-std::log(0.98) * 60.0).epsilon(1e-15));                      // measured 0 (equal)
  CHECK(std::abs(dropcheck::decay_per_step(s, 1.0 / 60.0) - 0.98) < 1e-15);  // measured 0 (equal)
  // At another step the same k decays by exp(-k*h), not by 0.98: f = 0.98^(1/2) at 1/120.
  CHECK(dropcheck::decay_per_step(s, 1.0 / 120.0) ==
        Approx(std::sqrt(0.98)).epsilon(1e-15));  // measured 0 (equal)
}

TEST_CASE("linear_damping is the rate k itself and linear_drag = 1 means no damping", "[loader]") {
  CHECK(dropcheck::parse_scene(loader_scene(kHead, kWorld + "linear_damping = 1.25\n", kBody),
                               "x.toml")
            .world.damping_rate == 1.25);
  CHECK(dropcheck::parse_scene(loader_scene(kHead, kWorld + "linear_drag = 1.0\n", kBody), "x.toml")
            .world.damping_rate == 0.0);
}

TEST_CASE("integers are accepted where numbers are expected", "[loader]") {
  const dropcheck::Scene s = dropcheck::parse_scene(
      "duration = 2\ntimestep = 1\n[world]\ngravity = [0, -10, 0]\n[[body]]\nname = "
      "\"a\"\nposition = [1, 2, 3]\nmass = 3\n",
      "x.toml");
  CHECK(s.duration == 2.0);
  CHECK(s.timestep.seconds == 1.0);
  CHECK(s.world.gravity.y() == -10.0);
  CHECK(s.bodies[0].mass == 3.0);
}

TEST_CASE("a force without bodies acts on every dynamic body and skips static ones", "[loader]") {
  const dropcheck::Scene s = dropcheck::parse_scene(
      loader_scene(kHead, kWorld,
                   "[[body]]\nname = \"floor\"\nposition = [0, 0, 0]\nstatic = true\n" + kBody +
                       "[[body]]\nname = \"b\"\nposition = [0, 0, 0]\n",
                   "[[force]]\nconstant = [2.0, 0.0, 0.0]\n"),
      "x.toml");
  REQUIRE(s.forces.size() == 1);
  CHECK(s.forces[0].bodies == std::vector<std::size_t>{1, 2});
}

TEST_CASE("an unknown key is rejected naming its full path, at every level", "[loader]") {
  check_error(loader_scene(kHead + "durration = 2.0\n", kWorld, kBody), "durration", "unknown key");
  check_error(loader_scene(kHead, kWorld + "gravityy = 1.0\n", kBody), "world.gravityy",
              "unknown key");
  check_error(loader_scene(kHead, kWorld, kBody + "colour = \"red\"\n"), "body[0].colour",
              "unknown key");
  check_error(loader_scene(kHead, kWorld, kBody, "[[force]]\nconstant = [1, 0, 0]\nstrength = 2\n"),
              "force[0].strength", "unknown key");
  check_error(
      loader_scene(kHead, kWorld, kBody,
                   "[[force]]\nspring = { anchor = [0, 5, 0], stiffness = 4.0, stiffnes = 5.0 }\n"),
      "force[0].spring.stiffnes", "unknown key");
}

TEST_CASE("an unknown key's message gives the line it is on", "[loader]") {
  // Lines: 1 duration, 2 [world], 3 gravity, 4 [[body]], 5 name, 6 position, 7 colour.
  CHECK_THAT(loader_error_of(loader_scene(kHead, kWorld, kBody + "colour = \"red\"\n")),
             Contains("x.toml:7: body[0].colour"));
}

TEST_CASE("a value of the wrong type is rejected naming the key and both types", "[loader]") {
  check_error(loader_scene(kHead, kWorld, kBody + "mass = \"heavy\"\n"), "body[0].mass",
              "expected a number, got a string");
  check_error(loader_scene(kHead, "[world]\ngravity = 9.8\n", kBody), "world.gravity",
              "expected an array of 3 numbers");
  check_error(loader_scene(kHead, "[world]\ngravity = [0.0, -9.8]\n", kBody), "world.gravity",
              "expected an array of 3 numbers");
  check_error(loader_scene(kHead, "[world]\ngravity = [0.0, \"down\", 0.0]\n", kBody),
              "world.gravity[1]", "expected a number, got a string");
  check_error(loader_scene(kHead, kWorld, kBody + "static = 1\n"), "body[0].static",
              "expected true or false, got an integer");
  check_error(loader_scene(kHead, kWorld + "contacts = \"yes\"\n", kBody), "world.contacts",
              "expected true or false, got a string");
  check_error(loader_scene(kHead + "name = 5\n", kWorld, kBody), "name",
              "expected a string, got an integer");
  check_error(loader_scene(kHead + "timestep = true\n", kWorld, kBody), "timestep",
              "expected seconds or \"1/N\", got a boolean");
  check_error(loader_scene(kHead, "world = 3\n", kBody), "world", "expected a table");
  check_error(loader_scene(kHead + "body = 3\n", kWorld, ""), "body", "expected [[body]] tables");
  check_error(loader_scene(kHead, kWorld, kBody, "[[force]]\nspring = 3\n"), "force[0].spring",
              "expected an inline table");
}

TEST_CASE("TOML nan and inf are rejected as non-finite naming the key", "[loader]") {
  check_error(loader_scene(kHead, kWorld, kBody + "mass = nan\n"), "body[0].mass",
              "must be finite");
  check_error(loader_scene(kHead, "[world]\ngravity = [0.0, -inf, 0.0]\n", kBody),
              "world.gravity[1]", "must be finite");
  check_error(
      loader_scene(kHead, kWorld, "[[body]]\nname = \"cube\"\nposition = [0.0, inf, 0.0]\n"),
      "body[0].position[1]", "must be finite");
  check_error(loader_scene("duration = inf\n", kWorld, kBody), "duration", "must be finite");
  check_error(loader_scene(kHead + "timestep = nan\n", kWorld, kBody), "timestep",
              "must be finite");
  check_error(loader_scene(kHead, kWorld + "linear_drag = nan\n", kBody), "world.linear_drag",
              "must be finite");
}

TEST_CASE("a mass <= 0 is rejected naming the key", "[loader]") {
  check_error(loader_scene(kHead, kWorld, kBody + "mass = 0.0\n"), "body[0].mass",
              "must be > 0 kg, got 0");
  check_error(loader_scene(kHead, kWorld, kBody + "mass = -2.0\n"), "body[0].mass",
              "must be > 0 kg, got -2");
}

TEST_CASE("a half extent <= 0 is rejected naming the key", "[loader]") {
  check_error(loader_scene(kHead, kWorld, kBody + "half_extents = [0.5, 0.0, 0.5]\n"),
              "body[0].half_extents", "> 0 m");
  check_error(loader_scene(kHead, kWorld, kBody + "half_extents = [0.5, 0.5, -1.0]\n"),
              "body[0].half_extents", "> 0 m");
}

TEST_CASE("linear_drag of 0 or 1.5 is rejected and so are both drag keys together", "[loader]") {
  check_error(loader_scene(kHead, kWorld + "linear_drag = 0.0\n", kBody), "world.linear_drag",
              "must be in (0, 1], got 0");
  check_error(loader_scene(kHead, kWorld + "linear_drag = 1.5\n", kBody), "world.linear_drag",
              "must be in (0, 1], got 1.5");
  check_error(loader_scene(kHead, kWorld + "linear_damping = -1.0\n", kBody),
              "world.linear_damping", "must be >= 0");
  check_error(loader_scene(kHead, kWorld + "linear_drag = 0.98\nlinear_damping = 1.2\n", kBody),
              "world.linear_damping", "not both");
}

TEST_CASE("duplicate body names are rejected naming the name", "[loader]") {
  check_error(loader_scene(kHead, kWorld, kBody + kBody), "body[1].name",
              "duplicate body name \"cube\"");
  check_error(loader_scene(kHead, kWorld, "[[body]]\nname = \"\"\nposition = [0, 0, 0]\n"),
              "body[0].name", "must not be empty");
}

TEST_CASE("a force on an unknown or a static body is rejected naming the body", "[loader]") {
  check_error(
      loader_scene(kHead, kWorld, kBody, "[[force]]\nbodies = [\"ghost\"]\nconstant = [1, 0, 0]\n"),
      "force[0].bodies[0]", "no body named 'ghost'");
  check_error(
      loader_scene(kHead, kWorld,
                   kBody + "[[body]]\nname = \"floor\"\nposition = [0, 0, 0]\nstatic = true\n",
                   "[[force]]\nbodies = [\"cube\", \"floor\"]\nconstant = [1, 0, 0]\n"),
      "force[0].bodies[1]", "body \"floor\" is static");
  check_error(loader_scene(kHead, kWorld, kBody, "[[force]]\nbodies = []\nconstant = [1, 0, 0]\n"),
              "force[0].bodies", "non-empty array");
}

TEST_CASE("a force needs exactly one law and a spring's parameters are checked", "[loader]") {
  check_error(loader_scene(kHead, kWorld, kBody, "[[force]]\nbodies = [\"cube\"]\n"),
              "force[0].constant", "exactly one");
  check_error(
      loader_scene(
          kHead, kWorld, kBody,
          "[[force]]\nconstant = [1, 0, 0]\nspring = { anchor = [0, 0, 0], stiffness = 1.0 }\n"),
      "force[0].constant", "exactly one");
  check_error(loader_scene(kHead, kWorld, kBody,
                           "[[force]]\nspring = { anchor = [0, 5, 0], stiffness = -1.0 }\n"),
              "force[0].spring.stiffness", "must be >= 0");
  check_error(loader_scene(kHead, kWorld, kBody, "[[force]]\nspring = { anchor = [0, 5, 0] }\n"),
              "force[0].spring.stiffness", "required key is missing");
}

TEST_CASE("a step count over the limit is rejected with the count and the limit", "[loader]") {
  // 1e9 s at 1/60 s is 6e10 steps; the limit is kMaxSteps = 2e7.
  check_error(loader_scene("duration = 1e9\n", kWorld, kBody), "timestep",
              "60000000000 steps, more than the limit of 20000000");
  // 1e300 s: a count no integer holds is still printed as a count, not an overflowed integer.
  check_error(loader_scene("duration = 1e300\n", kWorld, kBody), "timestep", "6e+301 steps");
}

TEST_CASE("a timestep longer than the duration or not dividing it is rejected", "[loader]") {
  check_error(loader_scene("duration = 0.01\n", kWorld, kBody), "timestep",
              "longer than the duration");
  check_error(loader_scene(kHead + "timestep = 0.3\n", kWorld, kBody), "timestep",
              "not a whole number of steps");
  check_error(loader_scene(kHead + "timesteps = [\"1/60\", \"1/30\", 0.7]\n", kWorld, kBody),
              "timesteps[2]", "not a whole number of steps");
  check_error(loader_scene("duration = 0.0\n", kWorld, kBody), "duration", "must be > 0 seconds");
}

TEST_CASE("timestep texts 1/0, abc and -0.1 are rejected quoting the text", "[loader]") {
  check_error(loader_scene(kHead + "timestep = \"1/0\"\n", kWorld, kBody), "timestep", "\"1/0\"");
  check_error(loader_scene(kHead + "timestep = \"abc\"\n", kWorld, kBody), "timestep", "\"abc\"");
  check_error(loader_scene(kHead + "timestep = \"-0.1\"\n", kWorld, kBody), "timestep",
              "> 0, got \"-0.1\"");
  check_error(loader_scene(kHead + "timestep = -0.1\n", kWorld, kBody), "timestep",
              "> 0, got \"-0.1\"");
  check_error(loader_scene(kHead + "timesteps = []\n", kWorld, kBody), "timesteps",
              "non-empty array");
}

TEST_CASE("a missing required key is rejected naming it", "[loader]") {
  check_error(loader_scene("", kWorld, kBody), "duration", "required key is missing");
  check_error(loader_scene(kHead, "[world]\nlinear_drag = 0.98\n", kBody), "world.gravity",
              "required key is missing");
  check_error(loader_scene(kHead, kWorld, "[[body]]\nname = \"cube\"\n"), "body[0].position",
              "required key is missing");
  check_error(loader_scene(kHead, kWorld, "[[body]]\nposition = [0, 0, 0]\n"), "body[0].name",
              "required key is missing");
  check_error(loader_scene(kHead, "", kBody), "world", "required table [world] is missing");
  check_error(loader_scene(kHead, kWorld, ""), "body", "at least one [[body]]");
}

TEST_CASE("a TOML syntax error gives the file and its line", "[loader]") {
  const std::string msg = loader_error_of(
      "duration = 1.0\n[world]\ngravity = [0.0, -9.8, 0.0]\nlinear_drag = = 0.98\n");
  CHECK_THAT(msg, Contains("x.toml:4: ") && Contains("TOML syntax error"));
}

TEST_CASE("a missing file is an InputError naming the path", "[loader]") {
  try {
    dropcheck::load_scene("no/such/dir/scene.toml");
    FAIL("loaded a file that does not exist");
  } catch (const dropcheck::InputError& e) {
    CHECK_THAT(e.what(), Contains("no/such/dir/scene.toml") && Contains("cannot read"));
  }
}

TEST_CASE("a directory given as the scene file is an InputError, not an empty scene", "[loader]") {
  try {
    dropcheck::load_scene(DROPCHECK_SOURCE_DIR "/scenarios");
    FAIL("loaded a directory");
  } catch (const dropcheck::InputError& e) {
    CHECK_THAT(e.what(), Contains("/scenarios: cannot read"));
  }
}

TEST_CASE("a control character in a scene or body name is refused, escaped or raw", "[loader]") {
  // TOML escapes decode to the bytes a terminal acts on: ESC (clear screen), BEL, NUL, tab, C1.
  check_error(loader_scene("name = \"a\\u001b[2Jb\"\n" + kHead, kWorld, kBody), "name",
              "control character '\\x1b' in a name");
  check_error(loader_scene("name = \"bell\\u0007\"\n" + kHead, kWorld, kBody), "name",
              "control character '\\x07'");
  check_error(loader_scene(kHead, kWorld, "[[body]]\nname = \"cu\\tbe\"\n"), "body[0].name",
              "control character '\\x09'");
  check_error(loader_scene(kHead, kWorld, "[[body]]\nname = \"nul\\u0000\"\n"), "body[0].name",
              "control character '\\x00'");
  check_error(loader_scene(kHead, kWorld, "[[body]]\nname = \"csi\\u009b\"\n"), "body[0].name",
              "control character '\\xc2\\x9b'");
  // Printable non-ASCII stays a valid name.
  CHECK(loader_error_of(loader_scene("name = \"w\\u00fcrfel\"\n" + kHead, kWorld, kBody)) ==
        "(loaded)");
}

TEST_CASE("an integer too large to be exactly a double is named as such", "[loader]") {
  // 2^53 + 1 = 9007199254740993 would become ...992 as a double: refused, not rounded.
  check_error(loader_scene(kHead, kWorld, kBody + "mass = 9007199254740993\n"), "body[0].mass",
              "the integer 9007199254740993 is too large to be exactly a double (beyond 2^53)");
  check_error(loader_scene(kHead, kWorld, kBody + "mass = -9007199254740993\n"), "body[0].mass",
              "too large to be exactly a double");
  // 2^53 itself is exact, and accepted as a number.
  CHECK(loader_error_of(loader_scene(kHead, kWorld, kBody + "mass = 9007199254740992\n")) ==
        "(loaded)");
}

TEST_CASE("rotation keys: defaults change nothing, given ones are kept, and the scene rotates",
          "[loader][rotation]") {
  const dropcheck::Scene plain =
      dropcheck::parse_scene(loader_scene(kHead, kWorld, kBody), "x.toml");
  const dropcheck::Body& b = plain.bodies[0];
  CHECK(b.orientation.coeffs() == dropcheck::Quat::Identity().coeffs());
  CHECK(b.angular_velocity == dropcheck::Vec3::Zero());
  // A uniform unit cube of 1 kg: m/12*(1 + 1) = 1/6 about every axis.
  CHECK(b.inertia.isApprox(dropcheck::Vec3::Constant(1.0 / 6.0), 1e-15));
  CHECK(plain.world.angular_damping_rate == 0.0);
  CHECK_FALSE(dropcheck::needs_rotation(plain));

  const dropcheck::Scene spun = dropcheck::parse_scene(
      loader_scene(kHead, "[world]\ngravity = [0.0, -9.8, 0.0]\nangular_drag = 0.98\n",
                   kBody +
                       "orientation = [0.0, 1.0, 0.0, 0.0]\nangular_velocity = [0.1, 5.0, 0.1]\n"
                       "inertia = [0.8083333333333333, 0.6833333333333333, 0.14166666666666666]\n",
                   "[[torque]]\nconstant = [0.0, 0.0, 2.0]\n"),
      "x.toml");
  CHECK(spun.bodies[0].orientation.x() == 1.0);
  CHECK(spun.bodies[0].angular_velocity == dropcheck::Vec3(0.1, 5.0, 0.1));
  CHECK(spun.bodies[0].inertia.z() == 0.14166666666666666);
  CHECK(spun.world.angular_damping_rate == Approx(-std::log(0.98) * 60.0));
  REQUIRE(spun.torques.size() == 1);
  CHECK(spun.torques[0].bodies == std::vector<std::size_t>{0});
  CHECK(spun.torques[0].torque == dropcheck::Vec3(0.0, 0.0, 2.0));
  CHECK(dropcheck::needs_rotation(spun));
}

TEST_CASE("a quaternion that is not unit, or moments no body has, are refused naming the key",
          "[loader][rotation]") {
  check_error(loader_scene(kHead, kWorld, kBody + "orientation = [0.7071, 0.7071, 0.0, 0.0]\n"),
              "body[0].orientation", "not a unit quaternion: its norm is 0.99999");
  check_error(loader_scene(kHead, kWorld, kBody + "orientation = [1.0, 0.0, 0.0]\n"),
              "body[0].orientation", "expected a unit quaternion [w, x, y, z]");
  check_error(loader_scene(kHead, kWorld, kBody + "inertia = [1.0, 0.0, 1.0]\n"), "body[0].inertia",
              "every principal moment must be > 0");
  check_error(loader_scene(kHead, kWorld, kBody + "inertia = [1.0, -1.0, 1.0]\n"),
              "body[0].inertia", "every principal moment must be > 0");
  check_error(loader_scene(kHead, kWorld, kBody + "inertia = [1.0, 1.0, 3.0]\n"), "body[0].inertia",
              "Izz = 3 exceeds the sum of the other two (2)");
  check_error(loader_scene(kHead, kWorld, kBody + "inertia = [5.0, 1.0, 3.0]\n"), "body[0].inertia",
              "Ixx = 5 exceeds the sum of the other two (4)");
  check_error(loader_scene(kHead, kWorld, kBody + "angular_velocity = [1.0, nan, 0.0]\n"),
              "body[0].angular_velocity[1]", "must be finite");
  check_error(loader_scene(kHead,
                           "[world]\ngravity = [0.0, 0.0, 0.0]\nangular_drag = 0.9\n"
                           "angular_damping = 1.0\n",
                           kBody),
              "world.angular_damping", "give angular_drag or angular_damping, not both");
  check_error(loader_scene(kHead, kWorld, kBody,
                           "[[torque]]\nbodies = [\"ghost\"]\nconstant = [1, 0, 0]\n"),
              "torque[0].bodies[0]", "no body named 'ghost'");
  // A flat plate's moments meet the triangle inequality with equality: accepted.
  CHECK(loader_error_of(loader_scene(kHead, kWorld, kBody + "inertia = [1.0, 2.0, 3.0]\n")) ==
        "(loaded)");
}

TEST_CASE("a published figure names a rotational member and a step, on a scene that rotates",
          "[loader][rotation]") {
  const std::string spin = kBody + "angular_velocity = [0.0, 0.0, 1.0]\n";
  const std::string good =
      "[[published]]\nsource = \"a paper\"\nengine = \"X\"\ndt = 0.001\n"
      "max_momentum_drift = 0.01\nlaw = \"explicit/first-order\"\n";
  CHECK(loader_error_of(loader_scene(kHead, kWorld, spin, good)) == "(loaded)");
  check_error(loader_scene(kHead, kWorld, spin,
                           "[[published]]\nsource = \"a paper\"\nengine = \"X\"\ndt = 0.001\n"
                           "max_momentum_drift = 0.01\nlaw = \"explicit\"\n"),
              "published[0].law", "expected a rotational member: one of no-gyro/first-order");
  check_error(loader_scene(kHead, kWorld, spin,
                           "[[published]]\nsource = \"a paper\"\nengine = \"X\"\ndt = 0.0\n"
                           "max_momentum_drift = 0.01\nlaw = \"explicit/first-order\"\n"),
              "published[0].dt", "must be > 0");
  check_error(loader_scene(kHead, kWorld, kBody, good), "published[0].law",
              "published rotation figures need a scene that rotates");
}

TEST_CASE("a static body may not turn, and a published member must fit the scene's duration",
          "[loader][rotation]") {
  const std::string floor =
      "[[body]]\nname = \"floor\"\nstatic = true\nposition = [0.0, -1.0, 0.0]\n";
  check_error(loader_scene(kHead, kWorld, kBody + floor + "angular_velocity = [0.0, 1.0, 0.0]\n"),
              "body[1].angular_velocity", "a static body does not turn");
  check_error(loader_scene(kHead, kWorld, kBody + floor + "orientation = [0.0, 1.0, 0.0, 0.0]\n"),
              "body[1].orientation", "a static body does not turn");
  const std::string spin = kBody + "angular_velocity = [0.0, 0.0, 1.0]\n";
  check_error(
      loader_scene(kHead, kWorld, spin,
                   "[[published]]\nsource = \"s\"\nengine = \"X\"\ndt = 0.001\n"
                   "max_momentum_drift = 0.01\nlaw = \"explicit/first-order\"\nlaw_dt = 1e-12\n"),
      "published[0].law_dt", "leave at most 1e7 steps");
}

TEST_CASE("contact keys: a sphere with its radius, friction and restitution load and are kept",
          "[loader][contact]") {
  const dropcheck::Scene plain =
      dropcheck::parse_scene(loader_scene(kHead, kWorld, kBody), "x.toml");
  CHECK(plain.bodies[0].shape == dropcheck::Shape::box);
  CHECK_FALSE(plain.bodies[0].friction.has_value());
  CHECK_FALSE(plain.bodies[0].restitution.has_value());
  CHECK_FALSE(dropcheck::scene_material(plain).friction.has_value());
  CHECK_FALSE(dropcheck::has_spheres(plain));

  const dropcheck::Scene ball = dropcheck::parse_scene(
      loader_scene(kHead, kWorld,
                   kBody + "shape = \"sphere\"\nradius = 0.25\nmass = 2.0\nfriction = 0.5\n"
                           "restitution = 0.9\n"),
      "x.toml");
  const dropcheck::Body& b = ball.bodies[0];
  CHECK(b.shape == dropcheck::Shape::sphere);
  CHECK(b.radius == 0.25);
  CHECK(b.half_extents == dropcheck::Vec3::Constant(0.25));  // its bounding box
  CHECK(b.inertia.isApprox(dropcheck::Vec3::Constant(0.4 * 2.0 * 0.0625), 1e-15));  // 2/5*m*r^2
  CHECK(*b.friction == 0.5);
  CHECK(*b.restitution == 0.9);
  CHECK(*dropcheck::scene_material(ball).friction == 0.5);
  CHECK(dropcheck::has_spheres(ball));
}

TEST_CASE("contact keys out of range or mixed between shapes are refused naming the key",
          "[loader][contact]") {
  check_error(loader_scene(kHead, kWorld, kBody + "shape = \"cone\"\n"), "body[0].shape",
              "expected \"box\" or \"sphere\", got 'cone'");
  check_error(loader_scene(kHead, kWorld, kBody + "shape = \"sphere\"\n"), "body[0].radius",
              "required key is missing");
  check_error(loader_scene(kHead, kWorld, kBody + "shape = \"sphere\"\nradius = 0.0\n"),
              "body[0].radius", "must be > 0 m");
  check_error(loader_scene(kHead, kWorld,
                           kBody + "shape = \"sphere\"\nradius = 1.0\n"
                                   "half_extents = [1.0, 1.0, 1.0]\n"),
              "body[0].half_extents", "a sphere has a radius");
  check_error(loader_scene(kHead, kWorld, kBody + "radius = 1.0\n"), "body[0].radius",
              "a box has half_extents");
  check_error(loader_scene(kHead, kWorld, kBody + "friction = -0.1\n"), "body[0].friction",
              "must be >= 0");
  check_error(loader_scene(kHead, kWorld, kBody + "restitution = 1.5\n"), "body[0].restitution",
              "must be in [0, 1]");
  check_error(loader_scene(kHead, kWorld, kBody + "friction = \"high\"\n"), "body[0].friction",
              "expected a number, got a string");
}

TEST_CASE("one friction and one restitution per scene: two bodies that differ are refused",
          "[loader][contact]") {
  const std::string floor =
      "[[body]]\nname = \"floor\"\nstatic = true\nposition = [0.0, -0.5, 0.0]\n";
  check_error(loader_scene(kHead, kWorld, kBody + "friction = 0.5\n" + floor + "friction = 0.3\n"),
              "body[1].friction",
              "one friction per scene (docs/contact.md): body \"cube\" sets 0.5");
  check_error(
      loader_scene(kHead, kWorld, kBody + "restitution = 0.5\n" + floor + "restitution = 0.0\n"),
      "body[1].restitution", "one restitution per scene");
  const dropcheck::Scene same = dropcheck::parse_scene(
      loader_scene(kHead, kWorld,
                   kBody + "friction = 0.5\n" + floor + "friction = 0.5\nrestitution = 0.2\n"),
      "x.toml");
  CHECK(*dropcheck::scene_material(same).friction == 0.5);
  CHECK(*dropcheck::scene_material(same).restitution == 0.2);
}

TEST_CASE("[expect] figures keep their text as written, and the description quotes it",
          "[loader]") {
  const std::string text =
      "description = \"stops at step {stop_step} after {stop_distance} m; "
      "{cube.rest_height} {tiny}\"\n" +
      kHead +
      "[expect]\r\nstop_step = 62\r\nstop_distance =\t2.5510 # a comment\n"
      "tiny = -1e-5\n[expect.cube]\nrest_height = 0.50\n" +
      kWorld + kBody;
  const dropcheck::Scene s = dropcheck::parse_scene(text, "x.toml");
  CHECK(s.description == "stops at step 62 after 2.5510 m; 0.50 -1e-5");
  REQUIRE(s.expect.size() == 4);
  CHECK(s.expect.at("stop_step").value == 62.0);
  CHECK(s.expect.at("stop_step").text == "62");
  CHECK(s.expect.at("stop_distance").value == 2.551);
  CHECK(s.expect.at("stop_distance").text == "2.5510");
  CHECK(s.expect.at("tiny").text == "-1e-5");
  CHECK(s.expect.at("cube.rest_height").text == "0.50");
  // An inline table, values without spaces around them.
  const dropcheck::Scene inline_table = dropcheck::parse_scene(
      "description = \"{a},{b}\"\n" + kHead + "expect = {a=1.50,b = 3}\n" + kWorld + kBody,
      "x.toml");
  CHECK(inline_table.description == "1.50,3");
}

TEST_CASE("a description without placeholders loads as written, braces are placeholders only",
          "[loader]") {
  CHECK(dropcheck::parse_scene("description = \"h = 1/60\"\n" + loader_scene(kHead, kWorld, kBody),
                               "x.toml")
            .description == "h = 1/60");
  check_error("description = \"a {b\"\n" + loader_scene(kHead, kWorld, kBody), "description",
              "a '{' never closed: '{b'");
  check_error("description = \"a} b\"\n" + loader_scene(kHead, kWorld, kBody), "description",
              "a '}' that closes no {placeholder}: 'a}'");
  check_error("description = \"{b}\"\n" + loader_scene(kHead, kWorld, kBody), "description",
              "'{b}' names no figure of [expect]");
}

TEST_CASE("an [expect] figure that is not a plain finite number is refused naming it", "[loader]") {
  const auto with = [](const std::string& figure) {
    return "description = \"{a}\"\n" + kHead + "[expect]\na = " + figure + "\n" + kWorld + kBody;
  };
  CHECK(loader_error_of(with("1.5")) == "(loaded)");
  check_error(with("\"62\""), "expect.a", "expected a number, got a string");
  check_error(with("true"), "expect.a", "expected a number, got a boolean");
  check_error(with("[1, 2]"), "expect.a", "expected a number, got an array");
  check_error(with("nan"), "expect.a", "must be finite");
  check_error(with("-inf"), "expect.a", "must be finite");
  check_error(with("9007199254740993"), "expect.a", "too large to be exactly a double");
  for (const char* written : {"0x3e", "1_000", "+5", "1E5", "5e+00_1"}) {
    INFO(written);
    const std::string msg = loader_error_of(with(written));
    CHECK_THAT(msg, Contains("expect.a: write a figure as a plain decimal number") ||
                        Contains("TOML syntax error"));
  }
  check_error(with("0x3e"), "expect.a", "got '0x3e'");
  check_error("description = \"{a}\"\n" + kHead + "expect = 5\n" + kWorld + kBody, "expect",
              "expected a table [expect]");
}

TEST_CASE("[expect] names are [a-z][a-z0-9_]*, and a table in it names a body", "[loader]") {
  const auto with = [](const std::string& description, const std::string& expect) {
    return "description = \"" + description + "\"\n" + kHead + expect + kWorld + kBody;
  };
  check_error(with("{Stop}", "[expect]\nStop = 1\n"), "expect.Stop", "[a-z][a-z0-9_]*");
  check_error(with("{_a}", "[expect]\n_a = 1\n"), "expect._a", "[a-z][a-z0-9_]*");
  check_error(with("x", "[expect]\n\"a b\" = 1\n"), "expect.a b", "[a-z][a-z0-9_]*");
  CHECK_THAT(loader_error_of(with("x", "[expect]\n\"a\\u001b[2J\" = 1\n")),
             Contains("expect.a\\x1b[2J: ") && !Contains("\x1b"));
  check_error(with("{ghost.a}", "[expect.ghost]\na = 1\n"), "expect.ghost",
              "no body named 'ghost'");
  check_error(with("{cube.x.a}", "[expect.cube.x]\na = 1\n"), "expect.cube.x",
              "expected a number, got a table");
  CHECK(loader_error_of(with("{cube.a}", "[expect.cube]\na = 1\n")) == "(loaded)");
}

TEST_CASE("an [expect] table holds at most 64 figures, each quoted by the description",
          "[loader]") {
  std::string description, expect = "[expect]\n";
  for (int i = 0; i < 65; ++i) {
    description += "{f" + std::to_string(i) + "} ";
    expect += "f" + std::to_string(i) + " = " + std::to_string(i) + "\n";
  }
  const std::string text = "description = \"" + description + "\"\n" + kHead + expect;
  CHECK_THAT(loader_error_of(text + kWorld + kBody),
             Contains("x.toml:") && Contains(": more than 64 figures in [expect]"));
  check_error("description = \"{a}\"\n" + kHead + "[expect]\na = 1\nb = 2\n" + kWorld + kBody,
              "expect.b", "the description never quotes it (write {b} where it states it)");
  CHECK_THAT(loader_error_of("description = \"{a}\"\n" + kHead + "[expect]\na = 1\nb = 2\n" +
                             kWorld + kBody),
             Contains("x.toml:5: expect.b: "));  // the line of b
  check_error("description = \"{a}\"\n" + kHead + "[expect]\na = 1\n[expect.cube]\nb = 2\n" +
                  kWorld + kBody,
              "expect.cube.b", "the description never quotes it (write {cube.b}");
}
