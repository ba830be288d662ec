// A fingerprint of a trajectory's exact numbers, for determinism checks and bit-identical
// baselines.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "harness/core/trajectory.hpp"

namespace dropcheck {

// FNV-1a (64-bit) over every recorded step index and the bit patterns of every position and
// velocity component (and, for a rotating run, of the orientation and angular velocity), in
// sample-major order. Equal hashes mean bit-identical samples; a run that does not rotate hashes
// exactly as before rotation existed.
std::uint64_t trajectory_hash(const Trajectory& t);

// The hash as 16 lower-case hex digits.
std::string trajectory_hash_hex(const Trajectory& t);

// The same FNV-1a (64-bit) over a byte string.
std::uint64_t fnv1a(std::string_view bytes);

// The same FNV-1a over a byte string, as 16 lower-case hex digits: a stable short name for a long
// one (harness/io/file_slug.hpp), the same on every build and machine.
std::string fnv1a_hex(std::string_view bytes);

}  // namespace dropcheck
