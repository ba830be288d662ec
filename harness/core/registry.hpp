// The registry: engine names to adapters compiled into this build (adapters/registry.cpp). What the
// harness knows of every engine, compiled in or not, is harness/core/engine_listing.hpp.
#pragma once

#include <memory>
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

// Why `name` is not available ("unknown engine", "not compiled in: ..."); empty when it is.
// Throws InputError for a malformed external engine name (an engine file with a bad key, ...).
std::string engine_unavailable_reason(const std::string& name);

}  // namespace dropcheck
