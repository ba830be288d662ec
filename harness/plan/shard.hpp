// Running a share of a plan: shard I of N (the cells whose key hashes to it, plan.hpp), or the
// cells a list names (what `merge` found missing). Their records go to one file of JSON lines,
// sorted by key, written whole or not at all.
#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "harness/plan/plan.hpp"

namespace dropcheck {

struct ShardSpec {
  std::size_t index = 0;  // 0-based
  std::size_t count = 1;
};

// "3/7" -> the third of seven (index 2). Throws InputError (key --shard) unless 1 <= I <= N and
// 1 <= N <= kMaxShards.
ShardSpec parse_shard(const std::string& text);
inline constexpr std::size_t kMaxShards = 100'000;

// "shard-03-of-12.jsonl": I padded to the digits of N, so that the files sort in shard order.
std::string shard_file_name(ShardSpec s);

// The plan's cells (indices, plan order) in shard s.
std::vector<std::size_t> cells_of_shard(const Plan& plan, ShardSpec s);

// The cells whose keys `path` lists, one per line (blank lines ignored), and the file name their
// records go to ("cells-<hash of the list>.jsonl"). Throws InputError naming the file and line of
// a key that is not in the plan.
std::vector<std::size_t> cells_from(const Plan& plan, const std::string& path,
                                    std::string& file_name);

// Runs `cells` (in one worker process: worker.hpp) and writes their records, one line each, sorted
// by key, to `out` atomically (a
// symbolic link at `out` is refused: the folder is shared by every shard). Prints one progress line
// per cell to `progress`. With a `cache` folder, a cell whose record this build already made
// (cell_identity: same key, scene text, measures and build, in any plan) is taken from it instead
// of run again, and every record made is kept there (cache/ab/abcdef....json, written atomically,
// links refused); an entry that is not such a record is ignored and replaced.
struct ShardSummary {
  std::size_t cells = 0, ok = 0, failed = 0, skipped = 0, cached = 0;
};
// `jobs` workers run the cells side by side (run_cells_in_worker); the file is the same bytes
// whatever their number.
ShardSummary run_cells(const Plan& plan, const std::vector<std::size_t>& cells,
                       const std::string& out, std::ostream& progress,
                       const std::string& cache = "", int jobs = 1);

}  // namespace dropcheck
