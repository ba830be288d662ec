// Baseline files in and out (baseline_io.cpp): the text format of baseline.hpp, written, compared
// and read back.
#pragma once

#include <optional>
#include <string>

#include "harness/guard/baseline.hpp"

namespace dropcheck {

// The file's text (format above). Throws InputError when a body name has whitespace in it.
std::string baseline_to_text(const Baseline& b);

// Reads and parses a baseline file; InputError when it is missing or malformed.
Baseline read_baseline(const std::string& path);

// read_baseline when `path` exists, nullopt when it does not (InputError when it is malformed).
std::optional<Baseline> read_baseline_if_present(const std::string& path);

// True when the two texts differ at most in their provenance and build_key lines: the same numbers,
// hence the same hash, so the file on disk is still true for the build it names.
bool same_data(const std::string& a, const std::string& b);

}  // namespace dropcheck
