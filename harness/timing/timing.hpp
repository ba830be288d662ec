// Run-time measurement: wall time per simulated second, from repeated runs after a warm-up. The
// work timed in one run is fixed by the scene, h and the engine's name alone (replicas_for,
// repeats_for, from each engine's nominal cost per body-step): never re-chosen from a measurement,
// so two runs of the report time the same work.
// Every round also times a fixed calibration loop (calibration.hpp), so that each engine's cost is
// also stated relative to a reference measured in the same rounds: a ratio a reader on another
// machine can compare.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"

namespace dropcheck {

struct TimingOptions {
  // A timed run should last at least this long (s) at the engine's nominal cost per body-step: the
  // scene is replicated (a power of two copies, at most max_replicas) until it does, so that a
  // cheap engine's run holds thousands of body-steps and an expensive one runs the scene as it
  // is written (copies cost an engine with a poor broad phase more than their share: DART's
  // bounce at 256 copies cost 12 times its cost at 16 per copy and step).
  double min_run_seconds = 5e-5;
  int max_replicas = 4096;
  // A timed sample should last at least this long (s) at the engine's nominal cost per body-step
  // (nominal_ns_per_body_step): the replicated run is repeated back to back (repeats_for), so that
  // a cheap engine (ours: ~4 ns per body-step) is timed over milliseconds, not microseconds.
  double min_sample_seconds = 2e-3;
  int max_repeats = 256;
  int warmups = 1;  // untimed rounds first (page faults, lazy initialisation)
  int samples = 8;  // timed rounds
  // An engine whose sample lasts longer than this (s) at its nominal cost is timed in the first
  // long_samples rounds only, without warm-up: a run that long warms itself in its first
  // milliseconds and varies less from sample to sample (simbody on Gazebo's boxes at 0.2 ms: one
  // run of 10 simulated seconds lasts 0.66 s, and 9 rounds of it cost 18 s of a report's 160).
  double long_sample_seconds = 1e-2;
  int long_samples = 3;
  // A run during which another process took the core (wall time beyond the thread's CPU time) is
  // run again, at most this many times.
  int retries = 1;
};

// A statistic of a cell's samples. kHeadline is the one the report leads with, plots and alerts
// on; the others are kept as columns.
enum class Statistic { min, q25, median };
const char* to_string(Statistic s);

// The figure that reproduces best between two reports on a shared machine, measured on this
// project's 2-core VM over three pairs of back-to-back reports, quiet, and four with a noisy
// neighbour (172 cells each): within 10 % in 98.8-100 % of cells with a median move of 1.3-2.5 %,
// where the median gave 98.8-100 % and 1.4-3.0 % (report.cpp kWhyHeadline, docs/timing.md). The
// machine's speed changes for seconds at a time and slows a run, never speeds it up, so the
// fastest of eight runs is the least disturbed one.
inline constexpr Statistic kHeadline = Statistic::min;

// The statistic of `samples` (0 for none); quantiles linear between order statistics.
double statistic(const std::vector<double>& samples, Statistic s);
// The statistic of `samples` over the same statistic of the calibration loop timed in the same
// rounds (the side-by-side ratio); 0 when there is no calibration.
double ratio_of(const std::vector<double>& samples, const std::vector<double>& calibration,
                Statistic s);
// The q-quantile of `samples` (0 <= q <= 1), linear between order statistics; 0 for none.
double quantile(std::vector<double> samples, double q);

struct Timing {
  std::string engine;
  double h = 0.0;
  int replicas = 1;   // copies of the scene's dynamic bodies in one timed run
  int repeats = 1;    // back-to-back runs (each loaded afresh, untimed) summed into one sample
  int disturbed = 0;  // runs measured again because another process took the core
  // Every timed sample in round order, wall seconds per simulated second of one copy: the full
  // harness loop (run_scene) and the engine's bare step() loop (no forces, reads or sampling).
  std::vector<double> full, bare;
  // The calibration loop (calibration.hpp) timed once in each of the same rounds, in seconds.
  std::vector<double> calibration;

  int samples() const { return static_cast<int>(full.size()); }
  double of(Statistic s) const { return statistic(full, s); }
  double bare_of(Statistic s) const { return statistic(bare, s); }
  double headline() const { return of(kHeadline); }
  // The headline over the calibration loop's, both measured in the same rounds: the engine's cost
  // in calibration loops per simulated second, which moves less with the machine than either.
  double ratio(Statistic s = kHeadline) const;
  // Harness overhead: (full loop - bare loop) / bare loop, from the medians.
  double overhead() const;
};

// Copies of `scene` one timed run of `engine` holds at step h: the smallest power of two with
// copies * (dynamic bodies, at least 1) * step_count(scene, h) * nominal_ns_per_body_step >=
// options.min_run_seconds, at most options.max_replicas. A function of the scene, h and the
// engine's name only.
int replicas_for(const Scene& scene, double h, const std::string& engine,
                 const TimingOptions& options);

// A rough cost of one body-step of `engine`'s bare loop (ns), declared with the engine
// (adapters/engines.txt, where each was measured: free cubes, and the report's contact cells for
// a scene with contacts), rounded down so that a sample lasts at least as long as targeted on a
// similar machine, never measured at run time; 1000 ns for an engine not listed (an external
// engine pays ~8 us per step for the protocol alone).
double nominal_ns_per_body_step(const std::string& engine, bool contacts = false);

// Back-to-back runs of the `replicas`-copy scene summed into one timed sample: the smallest power
// of two with repeats * replicas * body-steps per copy * nominal_ns_per_body_step(engine) >=
// options.min_sample_seconds, at most options.max_repeats. A function of the scene, h and the
// engine's name only.
int repeats_for(const Scene& scene, double h, const std::string& engine, int replicas,
                const TimingOptions& options);

// The scene copied `copies` times side by side: every body (static floors too, so that each copy
// lands on its own floor), copy c shifted by c*(x extent of the scene + 10 m) along x, so that the
// copies never touch and a planar scene stays planar; every force duplicated onto the copies (a
// spring's anchor shifted with its body).
Scene replicate(const Scene& scene, int copies);

// How one engine is timed on `scene` at step h: its copies (replicas_for), its runs per sample
// (repeats_for), and its timed rounds: options.samples, or for a sample longer than
// options.long_sample_seconds at its nominal cost options.long_samples rounds, unwarmed. A
// function of the scene, h and the engine's name only.
struct TimingPlan {
  int replicas = 1, repeats = 1, samples = 0;
  bool warmed = true;  // an untimed run before each sample (and the warm-up rounds)
};
TimingPlan timing_plan(const Scene& scene, double h, const std::string& engine,
                       const TimingOptions& options);

// Times every engine on `scene` at step h (one cell of the report): the rounds back to back
// (warm-ups first, untimed), each round timing the calibration loop, then running every engine
// once (an untimed bare loop to warm its code and data, then the timed full loop and the timed bare
// loop), in alternating order from round to round, so that drift of the machine hits all engines
// alike and each engine's samples are spread over the cell's window (an engine with long samples,
// timing_plan, runs unwarmed in the first rounds only). One Timing per engine, in order.
std::vector<Timing> time_engines(const std::vector<std::pair<std::string, EngineFactory>>& engines,
                                 const Scene& scene, double h, const TimingOptions& options = {});

}  // namespace dropcheck
