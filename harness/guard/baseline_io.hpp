// Baseline files in and out (baseline_io.cpp): the text format of baseline.hpp, written, compared
// and read back.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "harness/guard/baseline.hpp"

namespace dropcheck {

// Largest baseline file read. A baseline stores every 10th step: the largest run (kMaxSteps steps)
// of one body is 2e6 sample lines of about 150 bytes, 300 MB; the shipped ones are under 30 KiB.
inline constexpr std::int64_t kMaxBaselineBytes = std::int64_t{512} << 20;

// The file's text (format above). Throws InputError when a body name has whitespace in it.
std::string baseline_to_text(const Baseline& b);

// Reads and parses a baseline file; InputError when it is missing or malformed.
Baseline read_baseline(const std::string& path);

// read_baseline when `path` exists, nullopt when it does not (InputError when it is malformed).
std::optional<Baseline> read_baseline_if_present(const std::string& path);

// A baseline is checked against what it claims to be before anything is compared with it. Throws
// InputError naming `path` and the header field (scene, engine, scalar, dt, steps, bodies) when the
// stored baseline is about another scene, engine or scalar, or another step size, step count or
// set of bodies, than the fresh run `now` of the scene and engine it was read for.
void check_baseline_claims(const Baseline& stored, const Baseline& now, const std::string& path);

// Throws InputError when the file's name is not <scene>.<engine>.txt of the scene and engine its
// header names (file_slug): a baseline renamed into another's place is not compared as that one.
void check_baseline_file_name(const Baseline& b, const std::string& path);

// True when the two texts differ at most in their provenance and build_key lines: the same numbers,
// hence the same hash, so the file on disk is still true for the build it names.
bool same_data(const std::string& a, const std::string& b);

}  // namespace dropcheck
