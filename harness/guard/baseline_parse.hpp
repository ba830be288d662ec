// Parsing the baseline text format back into a Baseline, to the bit (baseline_parse.cpp).
#pragma once

#include <string>

#include "harness/guard/baseline.hpp"

namespace dropcheck {

// The first line of a baseline file, before its provenance (written by baseline_to_text).
inline constexpr const char* kProvenancePrefix = "# dropcheck baseline: ";

// Parses baseline_to_text's output exactly; `path` names the file in InputError messages.
Baseline parse_baseline(const std::string& text, const std::string& path);

}  // namespace dropcheck
