// A Trajectory in a compact binary form, for an isolated run's child to send its result to the
// parent over a pipe (harness/run/isolated_run.cpp). Same machine, same build: native byte
// order, doubles as their 8 bytes (bit-exact), strings and arrays prefixed by their length.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

#include "harness/core/trajectory.hpp"

namespace dropcheck {

// Writes `bytes` bytes or returns false (the other end closed, or an error).
using WireWrite = std::function<bool(const void* data, std::size_t bytes)>;
// Reads exactly `bytes` bytes or returns false (end of data, error, or time-out).
using WireRead = std::function<bool(void* data, std::size_t bytes)>;

// Sends `t` (only its first samples() rows of states). False when a write failed.
bool write_trajectory(const Trajectory& t, const WireWrite& write);

// Receives a trajectory written by write_trajectory. False when the data ended early or are not a
// trajectory of `bodies` bodies with at most `max_samples` samples (sizes are checked before any
// allocation, so corrupt data cannot ask for unbounded memory).
bool read_trajectory(Trajectory& t, std::size_t bodies, std::int64_t max_samples,
                     const WireRead& read);

}  // namespace dropcheck
