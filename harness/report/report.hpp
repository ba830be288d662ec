// The Markdown comparison report (reports/README.md) and its SVG plots. It knows results, not
// engines: everything comes in as SceneEvaluation (harness/study/evaluate.hpp), EngineInfo and
// Provenance. Deterministic except the columns marked as timings.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/provenance.hpp"
#include "harness/report/plot.hpp"
#include "harness/report/report_plots.hpp"
#include "harness/report/timing_record.hpp"
#include "harness/study/evaluate.hpp"

namespace dropcheck {

struct ReportInput {
  Provenance provenance;
  std::vector<EngineInfo> engines;  // the engines compiled in, in registry order
  std::vector<std::pair<std::string, std::string>> missing;  // engines not compiled in: name, why
  std::vector<SceneEvaluation> scenes;
  // The engine divergences are measured from (EvaluateOptions::reference), named in every header;
  // a scene it did not run says which engine stood in.
  std::string reference = "ours-f64";
  bool timing = true;            // timing columns, overhead and work-precision plots
  TimingOptions timing_options;  // as used, for the note on how timings are made
  std::string stability;         // Markdown of the stability section ("" when none)
  std::string stability_note;    // shown when `stability` is empty
  // The machine the timings are measured on (cmd_report: this_machine()), recorded with them.
  Machine machine;
  // The timings of the report this one replaces (its timings.json), to say how far each figure
  // moved; without a record, its note says why.
  PreviousTimings previous;
  // The timings the slowdown alert compares with: `report --compare-timings FILE`; without a
  // record here, the alert uses `previous` (slowdown_alert).
  PreviousTimings compare;
};

// The slowdown alert of a report whose timings are `now`: against `compare`, or without it against
// `previous`; the one place that chooses, for the report's section and `--fail-on-slowdown`.
struct SlowdownAlert {
  const TimingRecord* before = nullptr;  // nullptr: nothing to compare with (see `note`)
  std::string note;
  // Set when `before` was timed on another machine: the fields that differ ("cpu, installation";
  // harness/timing/machine.hpp). Nothing is judged then.
  std::string other_machine;
  std::vector<Slowdown> flagged;  // largest rise first
  std::size_t judged = 0;         // cells compared (timed the same way in both records)
};
SlowdownAlert slowdown_alert(const ReportInput& in, const TimingRecord& now);

// Outcome of drawing each plot: file -> "" when drawn, else why not.
using PlotOutcomes = std::vector<std::pair<std::string, std::string>>;

// The whole README.md, given the outcome of every plot.
std::string report_markdown(const ReportInput& input, const PlotOutcomes& plots);

// Draws every plot into `dir` and writes `dir`/README.md, and, with timings, `dir`/timings.json
// (timing_record.hpp). `dir` must exist (a staging directory:
// cmd_report moves it into place). Progress lines go to `progress`.
void write_report(const ReportInput& input, const std::string& dir, const Progress& progress = {});

}  // namespace dropcheck
