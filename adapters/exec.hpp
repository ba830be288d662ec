// External engines: any program that speaks the line protocol of docs/protocol.md on its stdin and
// stdout, named on the command line as `exec:PATH` or as an engine file `NAME.toml`:
//   name = "seed-python"                       # optional: overrides the name the engine announces
//   command = ["python3", "seed_engine.py"]    # required: program and arguments
//   timeout = 5.0                              # optional: seconds allowed per answer (default 5)
// The command runs in the engine file's directory, so relative paths in it are relative to the
// file.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"

namespace dropcheck {

// Seconds an external engine may take for one answer (handshake, scene, step) unless set.
inline constexpr double kDefaultExecTimeout = 5.0;

// How to start one external engine.
struct ExecSpec {
  std::vector<std::string> command;  // program and arguments (program searched in PATH if no '/')
  std::string cwd;                   // directory to run it in ("" = dropcheck's)
  std::string name;                  // overrides the announced name when not empty
  std::string file;                  // the engine file it came from ("" for exec:PATH)
  double timeout_s = kDefaultExecTimeout;  // per answer
};

// True for the engine names this adapter handles: "exec:..." or a name ending in ".toml".
bool is_exec_spec(const std::string& name);

// The spec behind an engine name. Throws InputError (file, key, problem) for a missing or malformed
// engine file, or an exec: path that is not an executable file.
ExecSpec parse_exec_spec(const std::string& name);

// Starts the engine and reads its handshake. A program that cannot start or answers badly still
// gives an Engine: its load() throws EngineError saying what went wrong (a result, not a crash).
std::unique_ptr<Engine> make_exec_engine(const ExecSpec& spec);

}  // namespace dropcheck
