// The report's timings kept beside it (timings.json), every sample of every cell, so that the next
// report written into the same folder can say how far each figure moved: the two-run measure of
// reproducibility, or, after a change of code or machine, what the change did to the run time, and
// whether a cell slowed down by more than two runs of the same code move (the slowdown alert).
// Wall-clock figures (⏱): the only part of a report folder that is not byte-stable.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/provenance.hpp"
#include "harness/io/link_policy.hpp"
#include "harness/study/evaluate.hpp"
#include "harness/timing/machine.hpp"
#include "harness/timing/timing.hpp"

namespace dropcheck {

// The file's name inside a report folder.
inline constexpr const char* kTimingsFile = "timings.json";

// What a comparison of two records looks at: a statistic of the samples in ms per simulated
// second, or the same over the calibration loop's (the side-by-side ratio).
struct TimingFigure {
  Statistic statistic = kHeadline;
  bool ratio = false;
};
std::string to_string(TimingFigure f);  // "minimum", "minimum / calibration", ...

// One timing cell: a scene, an engine and a step, with every sample.
struct TimedCell {
  std::string scene;
  std::string engine;
  std::string h;                       // the step as the scene writes it ("1/120")
  std::vector<double> full_ms;         // each sample, ms per simulated second (full harness loop)
  std::vector<double> bare_ms;         // the engine's bare step() loop, likewise
  std::vector<double> calibration_ms;  // the calibration loop in the same rounds, ms per run
  int replicas = 0;
  int repeats = 0;
  double value(TimingFigure f) const;  // 0 when there are no samples
};

// Every timing cell of one report, with what produced it.
struct TimingRecord {
  std::string commit;  // Provenance::commit
  std::string cpu;     // Provenance::cpu
  std::vector<TimedCell> cells;
  Machine machine;  // where the cells were timed (empty fields: a record that did not say)
};

// The timed cells of `scenes` (every engine that ran, every step of its sweep), in report order,
// timed on `machine`.
TimingRecord timing_record(const std::vector<SceneEvaluation>& scenes, const Provenance& p,
                           const Machine& machine);

// The record as JSON (nlohmann), one cell a line; parse_timing_record reads it back exactly.
std::string timing_json(const TimingRecord& record);

// Reads a record written by timing_json. Throws InputError naming `file`, the key and the problem
// when the text is not such a record (not JSON, a missing or mistyped key, a negative or
// non-finite median).
TimingRecord parse_timing_record(const std::string& text, const std::string& file);

// A timings.json named by the user (`report --compare-timings FILE`): a regular file of at most
// 16 MiB, read with parse_timing_record. Throws InputError naming the file and the problem.
// With Links::refuse a symbolic link at `file` is refused when it is opened (O_NOFOLLOW).
TimingRecord read_timing_record(const std::string& file, Links links = Links::follow);

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

// A cell found in both records: its figure before and now, and how far it moved: max/min - 1
// (0.1 = 10 %).
struct MovedCell {
  std::string scene, engine, h;
  double before = 0.0, now = 0.0;
  double moved = 0.0;
};

// Two records compared cell by cell (same scene, engine and step; a key found twice in either
// record is left out, as is a cell found in one record only).
struct TimingComparison {
  TimingFigure figure;           // what was compared
  std::size_t cells = 0;         // cells in both records
  std::size_t agree = 0;         // of them, figures within the tolerance
  double tolerance = 0.0;        // as given
  double median_moved = 0.0;     // the median of `moved` over the cells
  std::vector<MovedCell> worst;  // the cells that moved most, largest first
};

// `now` against `before` by `figure`: agreement within `tolerance`, and the `keep` cells that moved
// most.
TimingComparison compare_timings(const TimingRecord& before, const TimingRecord& now,
                                 TimingFigure figure = {}, double tolerance = 0.10,
                                 std::size_t keep = 5);

// What the slowdown alert compares: the headline over the calibration loop's, both measured in the
// same rounds. A machine that is slower for a while slows both, so this ratio moved about half as
// much as the headline between two reports of the same code (timing_record.cpp, kThresholds), and
// a report from another machine of the same kind compares by it too.
inline constexpr TimingFigure kAlertFigure{kHeadline, true};

// The slowdown alert: the cells whose kAlertFigure rose (now / before - 1) by more than
// slowdown_threshold of their engine, largest first. A cell found in one record only is not
// judged.
struct Slowdown {
  MovedCell cell;              // `moved` here is now / before - 1, signed
  double threshold = 0.0;      // the threshold it crossed
  double engine_median = 0.0;  // the median of `moved` over its engine's judged cells
};
// `judged` (when given) receives how many cells were compared: a cell of `now` is judged only when
// `before` holds it once, timed the same way (copies, repeats, number of samples) and finite, and
// only when both records were timed on the same machine (machine_differences empty): none else.
std::vector<Slowdown> slowdowns(const TimingRecord& before, const TimingRecord& now,
                                std::size_t* judged = nullptr);

// How far (now / before - 1) an engine's kAlertFigure may rise before it is called a slowdown: the
// largest move of the median over its cells measured between two reports of unchanged code, times
// 1.5 (adapters/engines.txt). A cell is flagged when its engine's median rose past it (the engine
// slowed, not one noisy cell) and the cell did too: one cell's noise (up to 17 % measured) never
// raises the alarm alone, and a 20 % slowdown of an engine moves every cell.
double slowdown_threshold(const std::string& engine);

}  // namespace dropcheck
