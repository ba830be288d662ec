// Fuzz target: the engine protocol's reading side (adapters/exec_protocol.cpp), what dropcheck
// reads from an external engine, on arbitrary bytes. The first byte picks the scene's body count
// (0-3); the rest, split at line feeds, is the engine's answers: handshake lines until "ready",
// then one "state N" line per step (read as a rotating scene's, 13 numbers per body, when the
// engine announced rotation). Every line must be taken or refused with ProtocolError, and
// whatever reaches a person must be inert and short: a refusal's message and every announced text
// (name, version, damping mapping) free of control characters and invalid UTF-8, a message under 1
// KiB. Anything else aborts: a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "adapters/exec_protocol.hpp"
#include "harness/core/input_error.hpp"

namespace {

void require_inert(const std::string& text, std::size_t max_bytes) {
  if (text.size() > max_bytes || dropcheck::find_unsafe_in_line(text) != std::string::npos)
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t bodies = data[0] % 4;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  dropcheck::EngineInfo info;
  dropcheck::HandshakeReader handshake(info, false, {"ours", "bullet"});
  std::vector<dropcheck::BodyState> states(bodies);
  std::vector<dropcheck::RotationState> turns(bodies);
  bool ready = false;
  std::int64_t step = 0;
  try {
    for (std::size_t at = 0; at <= text.size();) {
      std::size_t end = text.find('\n', at);
      if (end == std::string::npos) end = text.size();
      const std::string line = text.substr(at, end - at);
      at = end + 1;
      if (!ready) {
        ready = handshake.take(line);
        if (ready) {
          require_inert(info.name, 64);
          require_inert(info.version, 203);
          require_inert(info.damping_mapping, 203);
          if (info.name == "ours" || info.name == "bullet") std::abort();  // reserved
        }
      } else if (dropcheck::is_error_line(line)) {
        require_inert(dropcheck::error_text(line), 203);
      } else {
        if (info.capabilities.rotation != dropcheck::Rotation::none)
          dropcheck::parse_state_line(line, step++, states, turns);
        else
          dropcheck::parse_state_line(line, step++, states);
      }
    }
  } catch (const dropcheck::ProtocolError& e) {
    require_inert(e.what(), 1024);
  }
  return 0;
}
