// Comparing two result sets (directories of baseline files, harness/guard/baseline.hpp): which
// scenes and engines moved, by how much and from which step, and how the error-against-run-time
// curves shifted. The output is Markdown with fixed number formats and sorted rows, so it diffs
// cleanly.
#pragma once

#include <map>
#include <string>

#include "harness/guard/baseline.hpp"

namespace dropcheck {

// A directory of baseline files, e.g. tests/baselines/ or what `bless --out DIR` wrote.
struct ResultSet {
  std::string dir;
  std::map<std::string, Baseline> runs;  // by file name "<scene>.<engine>.txt", hence sorted
};

// Every *.txt baseline file in `dir`. InputError when `dir` is not a directory or a file is
// malformed.
ResultSet load_result_set(const std::string& dir);

// How one scene/engine pair compares between the two sets.
enum class Movement { identical, within_tolerance, moved, only_before, only_after, skipped };

// The Markdown summary of `after` against `before` (tolerance: regression_tolerance per scalar).
std::string diff_markdown(const ResultSet& before, const ResultSet& after);

// The verdict for one pair; `before`/`after` may be null when the pair is in one set only.
Movement classify(const Baseline* before, const Baseline* after);

// "identical", "within tolerance", "**moved**", "only before", "only after", "skipped".
const char* to_string(Movement m);

}  // namespace dropcheck
