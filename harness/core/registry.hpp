// The registry: engine names to adapters compiled into this build (adapters/registry.cpp). What the
// harness knows of every engine, compiled in or not, is harness/core/engine_listing.hpp.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"

namespace dropcheck {

// Every engine dropcheck knows, in report order, whether or not it is compiled in.
const std::vector<std::string>& known_engine_names();

// The engines compiled into this build, in report order.
std::vector<std::string> available_engine_names();

// A fresh engine by name; nullptr when the name is unknown or not compiled in. "exec:PATH" and
// "FILE.toml" name external engines (docs/protocol.md); a malformed one throws InputError.
std::unique_ptr<Engine> make_engine(const std::string& name);

// An external engine as a plan names it without starting it (a plan is data): its name (the engine
// file's `name` key, else the file's stem; for exec:PATH the program's file name) and a fingerprint
// of what it runs: FNV-1a over the engine file's bytes (its command's words among them) and over
// each file a word names (the program, a script; an interpreter found on PATH is not hashed),
// each by its file name and bytes, so that the same engine planned from another folder is the same
// engine. A changed engine file or script is another engine, so its cells are other cells.
struct ExternalEngineId {
  std::string name;         // 1-64 of A-Z a-z 0-9 . _ + -
  std::string fingerprint;  // 16 hex digits
  std::string id() const { return name + "@" + fingerprint; }
};

// nullopt for a registry name. Throws InputError for a malformed engine file, a name that is not a
// valid engine name, a command naming more than 32 files, or a file it runs over 64 MiB. `sweep`
// computes it again for each --engine-file, to compare with the plan's.
std::optional<ExternalEngineId> external_engine_id(const std::string& name);

// Whether `name` names an external engine (exec:PATH or FILE.toml), not a registry name.
bool is_external_engine_name(const std::string& name);

// Whether `id` has the form of an ExternalEngineId's id(): a valid engine name, '@', 16 hex digits.
bool is_external_engine_id(const std::string& id);

// Why `name` is not available ("unknown engine", "not compiled in: ..."); empty when it is.
// Throws InputError for a malformed external engine name (an engine file with a bad key, ...).
std::string engine_unavailable_reason(const std::string& name);

}  // namespace dropcheck
