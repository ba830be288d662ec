// The adapter contract. An engine is one row of adapters/engines.txt and one source,
// adapters/<source>.cpp, which defines, for each of its rows' names (with '-' as '_'):
//   std::unique_ptr<Engine> make_<name>();                 a fresh engine
//   double bare_seconds_<name>(const Scene& scene, double h);   its bare stepping loop
// adapters/CMakeLists.txt declares them and lists them in the registry's table (engine_table.inc),
// which registry.cpp alone reads.
//
// A bare loop loads `scene` at step h (untimed), then makes step_count(scene, h) calls of the
// engine's own step function through its own API, with no forces, reads, checks or sampling, and
// returns the wall seconds of those calls; it throws EngineError as load() does. The benchmark
// (bench/) compares the harness loop against it.
#pragma once

#include <string>

#include "harness/core/engine.hpp"

namespace dropcheck {

// The bare loop of the engine registered as `engine`; throws std::invalid_argument when it is not
// compiled into this build.
double bare_step_loop(const std::string& engine, const Scene& scene, double h);

}  // namespace dropcheck
