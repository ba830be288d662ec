// The regression guard: a fresh run of one scene on one engine against its golden baseline
// (harness/guard/baseline.hpp), in tiers, each a separate ctest entry (`ctest -L regression`):
//   1 bits         the trajectory hash is bit-identical; only when the build key (compiler, flags
//                  that change FP results) equals the baseline's, otherwise skipped with the reason
//   2 tolerance    every sample within a small absolute tolerance of the baseline (any build)
//   3 physics      the fresh run against the oracles, whatever the baseline says: it follows its
//                  own discrete law to rounding, and converges to the analytic solution at first
//                  order
//   determinism    two runs in one process give identical bytes (CSV) and hash
// A failure names scene, engine, body, first differing step, both values and by how much.
#pragma once

#include <optional>
#include <string>

#include "harness/guard/baseline.hpp"

namespace dropcheck {

// The four checks; each is its own ctest entry per scene and engine.
enum class Tier { bits, tolerance, physics, determinism };
// Outcome of one tier; skipped maps to exit code 77 (ctest SKIP_RETURN_CODE).
enum class TierVerdict { passed, failed, skipped };

// A verdict with the sentence a person reads in the ctest output.
struct TierResult {
  TierVerdict verdict = TierVerdict::passed;
  std::string message;  // "scene / engine / tier: ..." with the measured figures
};

// Tier 2's absolute tolerance on positions (m) and velocities (m/s) for an engine's scalar.
double regression_tolerance(Scalar scalar);

// Where two sampled trajectories of one scene and engine differ.
struct SampleDiff {
  std::string incomparable;    // why the samples cannot be compared (steps, bodies); "" if they can
  double max_dx = 0.0;         // max |dx| over samples and bodies (m)
  std::int64_t max_step = -1;  // where
  std::string max_body;
  std::int64_t first_step = -1;  // first sampled step with |dx| or |dv| > tolerance; -1 when none
  std::string first_body;
  std::string component;             // "y", "vx", ...: the component that differs most there
  double before = 0.0, after = 0.0;  // its values
  double first_delta = 0.0;          // |dx| (m) or |dv| (m/s) there
};

// Compares `after` with `before` sample by sample (same recorded steps and bodies required).
SampleDiff diff_samples(const Trajectory& before, const Trajectory& after, double tolerance);

// Tier 1: same hash as `expected` when both builds share a build key; skipped otherwise.
TierResult check_bits(const Baseline& expected, const Baseline& now);

// Tier 2: samples and sweep errors within regression_tolerance of `expected`.
TierResult check_tolerance(const Baseline& expected, const Baseline& now);

// Runs `scene` twice at its default step on fresh engines; identical CSV bytes and hash required.
TierResult check_determinism(const Scene& scene, const EngineFactory& make);

// "bits", "tolerance", "physics", "determinism".
const char* to_string(Tier tier);

// The tier named `name`; nullopt for an unknown name.
std::optional<Tier> parse_tier(const std::string& name);

// "passed", "FAILED", "skipped".
const char* to_string(TierVerdict verdict);

}  // namespace dropcheck
