// The engine protocol's reading side (docs/protocol.md): what an external engine answers, parsed
// and checked line by line, apart from the process that speaks it (adapters/exec.cpp) so that the
// part that reads a stranger's bytes can be fuzzed on its own (fuzz/exec_protocol_fuzz.cpp).
//
// Every refusal is a ProtocolError whose message quotes at most a short, escaped excerpt of what
// the engine sent (harness/core/input_error.hpp excerpt()): an engine's bytes never reach a
// terminal or a CI log raw, and a 1 MiB line never becomes a 1 MiB message.
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "harness/core/engine.hpp"

namespace dropcheck {

inline constexpr int kProtocolVersion = 1;

// An answer that breaks the protocol; its message is safe to print.
struct ProtocolError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Why `name` cannot name an external engine; empty when it can (1-64 of A-Z a-z 0-9 . _ + -, none
// of the `reserved` names: the built-in engines').
std::string engine_name_problem(const std::string& name, const std::vector<std::string>& reserved);

// The handshake, read line by line: "dropcheck-engine 1", then name, version, scalar, law,
// optional capabilities, rotation-law and damping-mapping lines, then "ready". An engine whose
// capabilities include rotation or rotation-z must declare its rotation-law.
class HandshakeReader {
 public:
  // Lines a handshake may take before "ready" (it needs 6; each line restarts the answer timeout,
  // so without a bound an engine could talk forever).
  static constexpr int kMaxHandshakeLines = 64;

  // `info` receives what the engine announces; `keep_name`: the engine file named it already;
  // `reserved`: names it may not announce (the built-in engines').
  HandshakeReader(EngineInfo& info, bool keep_name, std::vector<std::string> reserved)
      : info_(info), keep_name_(keep_name), reserved_(std::move(reserved)) {}
  // Takes the next line; true once "ready" closed a complete handshake. Throws ProtocolError.
  bool take(const std::string& line);

 private:
  void first(const std::vector<std::string>& t, const std::string& line);
  void key(const std::vector<std::string>& k, const std::string& line);

  EngineInfo& info_;
  bool keep_name_;
  std::vector<std::string> reserved_;
  bool started_ = false;
  int lines_ = 0;
  bool name_ = false, version_ = false, scalar_ = false, law_ = false, rotation_law_ = false;
};

// Reads "state N" followed by 6 numbers (x y z vx vy vz) per body of `out`, into `out`. Throws
// ProtocolError for another step, another count or a token that is not a number.
void parse_state_line(const std::string& line, std::int64_t n, std::span<BodyState> out);

// The same for a rotating scene: 13 numbers per body (x y z vx vy vz qw qx qy qz wx wy wz), the
// orientation and world angular velocity into `turns` (as many as `out`).
void parse_state_line(const std::string& line, std::int64_t n, std::span<BodyState> out,
                      std::span<RotationState> turns);

// True for an "error TEXT" line (the engine gives up, docs/protocol.md).
bool is_error_line(const std::string& line);
// The TEXT of an "error TEXT" line, control bytes escaped (\xNN), cut to at most 200 bytes (plus
// "..." after a cut); empty when `line` is not one.
std::string error_text(const std::string& line);

}  // namespace dropcheck
