// The report's timings kept beside it (timings.json), so that the next report written into the
// same folder can say how far each median moved: the two-run measure of reproducibility, or, after
// a change of code or machine, what the change did to the run time. Wall-clock figures (⏱): the
// only part of a report folder that is not byte-stable.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/provenance.hpp"
#include "harness/measure/evaluate.hpp"

namespace dropcheck {

// The file's name inside a report folder.
inline constexpr const char* kTimingsFile = "timings.json";

// One timing cell: a scene, an engine and a step, with its figures in ms per simulated second.
struct TimedCell {
  std::string scene;
  std::string engine;
  std::string h;  // the step as the scene writes it ("1/120")
  double median_ms = 0.0;
  double q1_ms = 0.0;
  double q3_ms = 0.0;
  double min_ms = 0.0;
  double bare_median_ms = 0.0;  // the engine's bare step() loop
  int samples = 0;
  int replicas = 0;
  int repeats = 0;
};

// Every timing cell of one report, with what produced it.
struct TimingRecord {
  std::string commit;  // Provenance::commit
  std::string cpu;     // Provenance::cpu
  std::vector<TimedCell> cells;
};

// The timed cells of `scenes` (every engine that ran, every step of its sweep), in report order.
TimingRecord timing_record(const std::vector<SceneEvaluation>& scenes, const Provenance& p);

// The record as JSON (nlohmann), one cell a line; parse_timing_record reads it back exactly.
std::string timing_json(const TimingRecord& record);

// Reads a record written by timing_json. Throws InputError naming `file`, the key and the problem
// when the text is not such a record (not JSON, a missing or mistyped key, a negative or
// non-finite median).
TimingRecord parse_timing_record(const std::string& text, const std::string& file);

// The timings of the report in `folder` that a new report will replace: read when `folder`/
// timings.json exists (a regular file of at most 16 MiB, not a symbolic link, parse_timing_record),
// else absent.
// Never throws: a missing or unreadable record leaves `record` empty and `note` says why.
struct PreviousTimings {
  std::optional<TimingRecord> record;
  std::string note;     // why there is no record, for the report ("" when there is one)
  std::string warning;  // the error that made an existing record unreadable ("" when none)
};
PreviousTimings read_previous_timings(const std::string& folder);

// A cell found in both records, and how far its median moved: max/min - 1 (0.1 = 10 %).
struct MovedCell {
  TimedCell before;
  TimedCell now;
  double moved = 0.0;
};

// Two records compared cell by cell (same scene, engine and step; a key found twice in either
// record is left out, as is a cell found in one record only).
struct TimingComparison {
  std::size_t cells = 0;         // cells in both records
  std::size_t agree = 0;         // of them, medians within the tolerance
  double tolerance = 0.0;        // as given
  double median_moved = 0.0;     // the median of `moved` over the cells
  std::vector<MovedCell> worst;  // the cells that moved most, largest first
};

// `now` against `before`: agreement within `tolerance`, and the `keep` cells that moved most.
TimingComparison compare_timings(const TimingRecord& before, const TimingRecord& now,
                                 double tolerance = 0.10, std::size_t keep = 5);

}  // namespace dropcheck
