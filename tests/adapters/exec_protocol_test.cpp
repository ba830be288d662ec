// Tests adapters/exec_protocol.cpp, what dropcheck reads from an external engine: the handshake and
// state lines are checked as before, and nothing an engine sends reaches a person raw: its version,
// damping mapping and error text keep no control character, and a refusal quotes a short excerpt.
#include "adapters/exec_protocol.hpp"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

using Catch::Matchers::Contains;
using namespace dropcheck;

namespace {

std::string protocol_refusal(const std::vector<std::string>& lines, std::size_t bodies = 1) {
  EngineInfo info;
  HandshakeReader handshake(info, false, {"ours"});
  std::vector<BodyState> states(bodies);
  std::int64_t step = 0;
  bool ready = false;
  try {
    for (const std::string& line : lines) {
      if (!ready)
        ready = handshake.take(line);
      else
        parse_state_line(line, step++, states);
    }
  } catch (const ProtocolError& e) {
    return e.what();
  }
  return "(accepted)";
}

const std::vector<std::string> kHandshake = {"dropcheck-engine 1", "name e",           "version 1",
                                             "scalar f64",         "law after-forces", "ready"};

// kHandshake with `extra` lines before its "ready".
std::vector<std::string> handshake(const std::vector<std::string>& extra) {
  std::vector<std::string> lines(kHandshake.begin(), kHandshake.end() - 1);
  lines.insert(lines.end(), extra.begin(), extra.end());
  lines.push_back("ready");
  return lines;
}

}  // namespace

TEST_CASE("a complete handshake and state lines are accepted", "[exec]") {
  std::vector<std::string> lines = kHandshake;
  lines.push_back("state 0 0 10 0 0 0 0");
  lines.push_back("state 1 1e308 -5e-324 0 0 -0.5 0");
  CHECK(protocol_refusal(lines) == "(accepted)");
}

TEST_CASE("text an engine announces is kept with its control characters escaped", "[exec]") {
  EngineInfo info;
  HandshakeReader handshake(info, false, {});
  for (const std::string line :
       {"dropcheck-engine 1", "name e", "version 2.0\x1b[2J\x07", "scalar f64", "law after-forces",
        "damping-mapping phi\x1b]0;title\x07"})
    CHECK_FALSE(handshake.take(line));
  CHECK(handshake.take("ready"));
  CHECK(info.version == "2.0\\x1b[2J\\x07");
  CHECK(info.damping_mapping == "phi\\x1b]0;title\\x07");
  CHECK(error_text("error disk\x1b[31m full") == "disk\\x1b[31m full");
  CHECK(error_text(std::string("error ") + std::string(5000, 'x')).size() == 203);
  CHECK(error_text("errors are fine") == "");
  // Escapes count against the 200 bytes (found by fuzz/exec_protocol_fuzz.cpp): 300 ESC bytes keep
  // 50 escapes, never half of one.
  const std::string escaped = error_text("error " + std::string(300, '\x1b'));
  CHECK(escaped.size() == 203);
  CHECK(escaped.substr(196) == "\\x1b...");
}

TEST_CASE("a refusal quotes at most a short, escaped excerpt of the engine's line", "[exec]") {
  CHECK(protocol_refusal({"hello \x1b[2J"}) ==
        "garbage from the engine: expected 'dropcheck-engine 1', got 'hello \\x1b[2J'");
  std::vector<std::string> lines = kHandshake;
  lines.push_back("state 0 " + std::string(1'000'000, '9') + " 0 0 0 0 0");
  const std::string huge = protocol_refusal(lines);
  CHECK_THAT(huge, Contains("garbage from the engine: expected a number, got '999"));
  CHECK(huge.size() < 200);
  CHECK_THAT(protocol_refusal({"dropcheck-engine 1", "name ours"}),
             Contains("'ours' is the name of a built-in engine"));
  CHECK_THAT(protocol_refusal({"dropcheck-engine 1", "name \x1b[2J"}),
             Contains("'\\x1b[2J' is not a valid engine name"));
  CHECK_THAT(protocol_refusal({"dropcheck-engine 1", "name e", "ready"}),
             Contains("the handshake lacks version"));
  std::vector<std::string> endless{"dropcheck-engine 1"};
  endless.resize(100, "version 1");
  CHECK_THAT(protocol_refusal(endless),
             Contains("a handshake of more than 64 lines without 'ready'"));
}

TEST_CASE("an engine that turns bodies announces it with its rotational member",
          "[exec][rotation]") {
  EngineInfo info;
  HandshakeReader reader(info, false, {"ours"});
  for (const std::string& line :
       handshake({"capabilities rotation", "rotation-law implicit-body/exp-map"}))
    reader.take(line);
  CHECK(info.capabilities.rotation == Rotation::full);
  CHECK(info.rotation_law ==
        RotationLaw{Gyroscopic::implicit_body, OrientationUpdate::exponential_map});
  CHECK_THAT(protocol_refusal(handshake({"capabilities rotation"})),
             Contains("announces rotation but lacks 'rotation-law KEY'"));
  CHECK_THAT(protocol_refusal(handshake({"capabilities rotation-z", "rotation-law explicit"})),
             Contains("garbage from the engine") && Contains("rotation-law keys"));
  CHECK(protocol_refusal(handshake({"capabilities rotation-z", "rotation-law no-gyro/exp-map"})) ==
        "(accepted)");
}

TEST_CASE("a rotating scene's state line carries 13 numbers per body", "[exec][rotation]") {
  std::vector<BodyState> states(2);
  std::vector<RotationState> turns(2);
  parse_state_line("state 3 1 2 3 4 5 6 1 0 0 0 0 0 1  7 8 9 1 2 3 0.5 0.5 0.5 0.5 -1 -2 -3", 3,
                   states, turns);
  CHECK(states[1].position == Vec3(7, 8, 9));
  CHECK(turns[0].angular_velocity == Vec3(0, 0, 1));
  CHECK(turns[1].orientation.coeffs() == Eigen::Vector4d(0.5, 0.5, 0.5, 0.5));  // x y z w
  CHECK(turns[1].angular_velocity == Vec3(-1, -2, -3));
  try {
    parse_state_line("state 3 1 2 3 4 5 6 7 8 9 1 2 3", 3, states, turns);
    FAIL("accepted 12 numbers for 2 rotating bodies");
  } catch (const ProtocolError& e) {
    CHECK_THAT(e.what(), Contains("13 per body in a rotating scene"));
  }
}

TEST_CASE("an engine that collides materials and spheres announces them with its contact laws",
          "[exec][contact]") {
  EngineInfo info;
  HandshakeReader reader(info, false, {"ours"});
  for (const std::string& line :
       handshake({"capabilities contacts friction restitution spheres",
                  "friction-model box-pyramid", "bounce-law 0.2 0.3 velocity 0.5 0 0.02"}))
    reader.take(line);
  CHECK(info.capabilities.friction);
  CHECK(info.capabilities.restitution);
  CHECK(info.capabilities.spheres);
  CHECK(info.friction_model == FrictionModel::box_pyramid);
  CHECK(info.bounce_law.erp == 0.2);
  CHECK(info.bounce_law.max_push == 0.3);
  CHECK_FALSE(info.bounce_law.push_in_position);
  CHECK(info.bounce_law.threshold == 0.5);
  CHECK(info.bounce_law.contact_distance_per_size == 0.02);
  CHECK(protocol_refusal(handshake({"bounce-law 0 inf position 0 0 0"})) == "(accepted)");
  // DART's law, with the four optional members.
  EngineInfo dart;
  HandshakeReader dart_reader(dart, false, {"ours"});
  for (const std::string& line :
       handshake({"capabilities contacts restitution spheres",
                  "bounce-law 0.01 0.001 velocity 0.1 0 0 after-gravity rebound 100 1e-05 touch"}))
    dart_reader.take(line);
  CHECK(dart.bounce_law.free_approach);
  CHECK(dart.bounce_law.threshold_on_rebound);
  CHECK(dart.bounce_law.max_rebound == 100.0);
  CHECK(dart.bounce_law.cfm == 1e-5);
  CHECK(dart.bounce_law.touching);
  for (const char* bad : {"bounce-law 1.5 inf velocity 0 0 0", "bounce-law 0.2 0 velocity 0 0 0",
                          "bounce-law 0.2 inf sideways 0 0 0", "bounce-law 0.2 inf velocity -1 0 0",
                          "bounce-law 0.2 inf velocity nan 0 0", "bounce-law 0.2 inf velocity 0 0",
                          "bounce-law 0 inf velocity 0 0 0 after-gravity rebound 100 0",
                          "bounce-law 0 inf velocity 0 0 0 late rebound 100 0 touch",
                          "bounce-law 0 inf velocity 0 0 0 step-start speed 100 0 touch",
                          "bounce-law 0 inf velocity 0 0 0 step-start approach 100 0 contact",
                          "bounce-law 0 inf velocity 0 0 0 step-start approach 0 0 touch",
                          "bounce-law 0 inf velocity 0 0 0 step-start approach inf -1 touch",
                          "friction-model pyramid"})
    CHECK_THAT(protocol_refusal(handshake({bad})), Contains("garbage from the engine"));
  CHECK_THAT(protocol_refusal(handshake({"capabilities restitution spheres"})),
             Contains("without 'contacts'"));
}

TEST_CASE("an engine announces its stack law", "[exec][contact][stack]") {
  EngineInfo info;
  HandshakeReader reader(info, false, {"ours"});
  for (const std::string& line :
       handshake({"capabilities contacts", "stack-law 5e-10 4 0 0 10 5e-5 0.01 0.003"}))
    reader.take(line);
  CHECK(info.stack_law.compliance == 5e-10);
  CHECK(info.stack_law.points == 4);
  CHECK(info.stack_law.iterations == 10);
  CHECK(info.stack_law.sink_bound == 5e-5);
  CHECK(info.stack_law.drift_bound == 0.01);
  CHECK(info.stack_law.still_bound == 0.003);
  for (const char* bad :
       {"stack-law 0 0 0 0 0 0 0.001 0.001", "stack-law 0 4.5 0 0 0 0 0.001 0.001",
        "stack-law 0 4 0 0 2.5 0 0.001 0.001", "stack-law -1 4 0 0 0 0 0.001 0.001",
        "stack-law 0 4 0 0 0 0 inf 0.001", "stack-law 0 4 0 0 0 0 0.001"})
    CHECK_THAT(protocol_refusal(handshake({bad})), Contains("garbage from the engine"));
}

TEST_CASE("A contact-solver line that dropcheck cannot read is refused at the handshake",
          "[exec][contact]") {
  for (const char* line :
       {"contact-solver", "contact-solver lcp", "contact-solver sequential-impulses 0 0.001",
        "contact-solver sequential-impulses 2.5 0.001", "contact-solver soft 2",
        "contact-solver soft nan", "contact-solver exact 1"}) {
    EngineInfo info;
    HandshakeReader reader(info, false, {});
    reader.take("dropcheck-engine 1");
    INFO(line);
    CHECK_THROWS_WITH(reader.take(line),
                      Catch::Contains("contact-solver sequential-impulses ITERATIONS"));
  }
  EngineInfo info;
  HandshakeReader reader(info, false, {});
  reader.take("dropcheck-engine 1");
  reader.take("contact-solver sequential-impulses 10 0.001");
  CHECK(info.contact_solver.kind == ContactSolverKind::sequential_impulses);
  CHECK(info.contact_solver.velocity_iterations == 10);
  CHECK(info.contact_solver.coulomb_median_bound == 0.001);
}
