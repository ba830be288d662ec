// A sweep's result file (docs/results.md) as the report reads it: one SweepCell per record line,
// the fields `dropcheck report --results` draws and lists. Lines are read one at a time, each
// bounded, so a reader's memory is one line whatever the file holds.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace dropcheck {

// What the report reads of one record.
struct SweepCell {
  std::string key, scene, engine, status, reason;
  std::vector<std::pair<std::string, std::string>> axes;  // in the sweep's order
  std::optional<double> error;                            // error.closed_form.max_dx (m)
  std::optional<double> theory_max_h;                     // stability.theory_max_h (s)
  std::string law_unstable;
  std::optional<double> ns_per_body_step;  // timing (wall time)
  std::string cpu;
};

// Largest result file read: 4 GiB.
inline constexpr long long kMaxResultBytes = 4LL << 30;
// Longest record line read (bytes): a record of dropcheck's is under 2 KiB.
inline constexpr std::size_t kMaxResultLine = 1 << 20;

// Reads a result file. Throws InputError naming the file and line for a line that is not a record
// (or longer than kMaxResultLine), naming the file for one that is not a regular file, larger than
// kMaxResultBytes or holds no record.
std::vector<SweepCell> read_sweep_results(const std::string& path);

// The same from the file's text (lines end at "\n" or "\r\n"); `name` names it in messages (what
// the fuzz target reads: fuzz/record_reader_fuzz.cpp).
std::vector<SweepCell> parse_sweep_results(std::string_view text, const std::string& name);

}  // namespace dropcheck
