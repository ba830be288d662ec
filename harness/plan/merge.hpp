// Merging a plan's shard files into one result file: every record once, sorted by key, so that the
// result is the same bytes however the plan was split (N = 1, 7 or 1000) and wherever it ran.
#pragma once

#include <string>
#include <unordered_set>
#include <vector>

#include "harness/plan/plan.hpp"

namespace dropcheck {

struct MergeResult {
  std::size_t files = 0;             // shard files read
  std::size_t records = 0;           // distinct cells recorded
  std::vector<std::string> missing;  // keys of the plan's cells no file holds, in plan order
};

// Reads every shard file in `dir` ("shard-*.jsonl", "cells-*.jsonl"; anything else is left alone).
// Throws InputError naming the file and line for a line that is not a record of this plan (another
// plan's hash, a key the plan does not have, not JSON), for a shard entry that is a symbolic link
// or not a regular file, and naming both files for one cell recorded twice with different bytes
// (the same bytes twice are one record: a shard rerun beside its first run). When no cell is
// missing, writes the records, one line each in key order, to `out` atomically.
MergeResult merge_shards(const Plan& plan, const std::string& dir, const std::string& out);

// The keys of `plan`'s cells, what record_key looks a record's key up in.
std::unordered_set<std::string> cell_keys(const Plan& plan);

// The key of one record line, `text` (line `line` of `file`, both as messages give them), after
// checking that it belongs to `plan` (`keys`: cell_keys(plan)). Throws InputError naming the file
// and line for a line that is not JSON, not a dropcheck-record/1 record, a record of another plan
// (its hash) or of a cell the plan does not have. What merge_shards checks each line with (the
// fuzz target: fuzz/record_reader_fuzz.cpp).
std::string record_key(const Plan& plan, const std::unordered_set<std::string>& keys,
                       const std::string& file, long long line, const std::string& text);

// Largest shard file read: 4 GiB.
inline constexpr long long kMaxShardBytes = 4LL << 30;
// Longest record line read (bytes): a record of dropcheck's is under 2 KiB.
inline constexpr std::size_t kMaxRecordLine = 1 << 20;

}  // namespace dropcheck
