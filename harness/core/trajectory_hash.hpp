// A fingerprint of a trajectory's exact numbers, for determinism checks and bit-identical
// baselines.
#pragma once

#include <cstdint>
#include <string>

#include "harness/core/trajectory.hpp"

namespace dropcheck {

// FNV-1a (64-bit) over every recorded step index and the bit patterns of every position and
// velocity component, in sample-major order. Equal hashes mean bit-identical samples.
std::uint64_t trajectory_hash(const Trajectory& t);

// The hash as 16 lower-case hex digits.
std::string trajectory_hash_hex(const Trajectory& t);

}  // namespace dropcheck
