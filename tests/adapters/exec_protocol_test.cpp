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

std::string refusal(const std::vector<std::string>& lines, std::size_t bodies = 1) {
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

}  // namespace

TEST_CASE("a complete handshake and state lines are accepted", "[exec]") {
  std::vector<std::string> lines = kHandshake;
  lines.push_back("state 0 0 10 0 0 0 0");
  lines.push_back("state 1 1e308 -5e-324 0 0 -0.5 0");
  CHECK(refusal(lines) == "(accepted)");
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
  CHECK(refusal({"hello \x1b[2J"}) ==
        "garbage from the engine: expected 'dropcheck-engine 1', got 'hello \\x1b[2J'");
  std::vector<std::string> lines = kHandshake;
  lines.push_back("state 0 " + std::string(1'000'000, '9') + " 0 0 0 0 0");
  const std::string huge = refusal(lines);
  CHECK_THAT(huge, Contains("garbage from the engine: expected a number, got '999"));
  CHECK(huge.size() < 200);
  CHECK_THAT(refusal({"dropcheck-engine 1", "name ours"}),
             Contains("'ours' is the name of a built-in engine"));
  CHECK_THAT(refusal({"dropcheck-engine 1", "name \x1b[2J"}),
             Contains("'\\x1b[2J' is not a valid engine name"));
  CHECK_THAT(refusal({"dropcheck-engine 1", "name e", "ready"}),
             Contains("the handshake lacks version"));
  std::vector<std::string> endless{"dropcheck-engine 1"};
  endless.resize(100, "version 1");
  CHECK_THAT(refusal(endless), Contains("a handshake of more than 64 lines without 'ready'"));
}
