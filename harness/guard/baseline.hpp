// Golden baselines: what one engine did on one scene, in a diff-friendly text file with exact
// numbers, so that a change to an integrator shows at once what moved
// (harness/guard/regression.hpp).
//
// One file per scene and engine, <scene>.<engine>.txt; a directory of them is a "result set"
// (tests/baselines/ is the committed one; `dropcheck bless --out DIR` writes one anywhere). Format,
// one record per line, numbers printed with %.17g so that they read back to the bit:
//
// clang-format off
//   # dropcheck baseline: made by `dropcheck bless` with <toolchain>, <build type> "<flags>", on <commit>
//   build_key x86_64, GNU 12.2.0, Eigen 3.4.0, glibc 2.36, -O2 -ffp-contract=off
//                                           (the bits tier's key; one line per build known to give
//                                           these numbers)
//   scene free_fall_drag / engine ours-f64 / scalar f64 / law v = phi*(v + a*h); x += h*v
//   analytic closed form                    (or why there is none: "contacts", ...)
//   skipped no contacts                     (instead of everything below, when it cannot run)
//   dt 1/60 0.016666666666666666 / steps 60 / record_every 10 / status ok / hash 3f2a...
//   sweep h=1/30 steps=30 status=ok analytic_max_dx=... analytic_final_dx=... law_max_dx=...
//         law_worst_body=cube law_first_over=-1            (one line per h of the scene's sweep)
//   timing h=1/60 min_per_sim_s=... median_per_sim_s=... replicas=...   (only with --timing)
//   bodies cube
//   sample STEP BODY x y z vx vy vz         (every record_every-th step and the last, at dt)
// clang-format on
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"
#include "harness/judge/own_law.hpp"

namespace dropcheck {

// "No value" in a baseline (no closed form, no timing): NaN, written "nan".
inline constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

// One step size of the scene's sweep: errors against both oracles, and optionally the run time.
struct SweepPoint {
  Timestep dt;
  std::int64_t steps = 0;
  std::string status = "ok";          // to_string(RunStatus) at this h (one word)
  double analytic_max_dx = kNoValue;  // max over steps and bodies of |x - oracle 1| (m); NaN: none
  double analytic_final_dx = kNoValue;  // the same at the last step (m)
  double law_max_dx = 0.0;              // max over steps and bodies of |x - oracle 2| (m), oracle 2
                                        // in the engine's own arithmetic (own_arithmetic.hpp)
  std::string law_worst_body;           // the body with that maximum
  std::int64_t law_first_over = -1;  // first step where it exceeds the own-law tolerance; -1 never
  // Judged on a fresh run only (not in the file): the own-law verdict at this h, and the member of
  // the law family the run follows instead when it leaves its declared law.
  std::optional<OwnLawVerdict> own_law;
  std::optional<Law> fits;
  // When the run's rotation leaves its declared rotational member: the member it follows instead
  // (identify_rotation; "A or B" when the scene cannot tell them apart), as "GYRO/UPDATE" keys.
  std::string rotation_fits;
  double wall_min = kNoValue;  // wall seconds per simulated second (--timing only)
  double wall_median = kNoValue;
  int replicas = 0;  // copies of the scene in one timed run (--timing only)
};

// A figure of what a run's contacts did ("cube.stop_step" 62, "ball.apex_1" 0.2378), so that a
// diff can say what moved in contact terms.
struct ContactFigure {
  std::string name;  // BODY.FIGURE
  double value = 0.0;
};

// One scene on one engine: the golden record that the regression tiers compare a fresh run with.
inline constexpr std::size_t kMaxBuildKeys = 16;

struct Baseline {
  std::string provenance;  // the "# dropcheck baseline: made by ..." line (not compared)
  // BuildId::key of the build that made it, then of each build that `bless` later found to give
  // the same numbers (one `build_key` line each, at most kMaxBuildKeys): the bits tier runs on
  // any of them.
  std::vector<std::string> build_keys;
  std::string scene, engine;
  Scalar scalar = Scalar::f64;
  std::string law;       // to_string(DampingOrder) the engine declares
  std::string analytic;  // "closed form", or why the scene has none
  std::string skipped;   // why the engine cannot run the scene; empty when it ran
  Timestep dt;           // the scene's default step
  std::int64_t record_every = 10;
  std::string status = "ok";  // run status at dt, with the failure when not ok
  std::string hash;           // trajectory_hash_hex of the run at dt, every step recorded
  Trajectory samples;         // the run at dt, every record_every-th step and the last
  std::vector<SweepPoint>
      sweep;                 // scene_sweep(scene) (harness/study/sweep.hpp): largest step first
  std::string failed_tiers;  // written as a "# FAILED ..." comment by `bless --out` (not parsed)
  // The run at dt in contact terms (contact_figures): each slide's stop step (-1: never) and
  // distance, each bounce's first contact step and first three apexes, each landing's first
  // contact step and rest offset, each stacked level's sink.
  std::vector<ContactFigure> contact;
};

// At most this many contact figures in a baseline (the reader's bound).
inline constexpr std::size_t kMaxContactFigures = 4096;

// What `run` (every step kept) shows of the slides and bounces of `scene` (contact_laws.hpp), of
// its landings (landing.hpp: the bodies alone over a floor that neither slide nor bounce) and of
// its stacks (stack.hpp): at most kMaxContactFigures, the rest left out.
std::vector<ContactFigure> contact_figures(const Scene& scene, const Trajectory& run);

// How make_baseline samples and whether it times.
struct BaselineOptions {
  std::int64_t record_every = 10;  // sampling of the stored trajectory
  bool timing = false;  // measure wall time per simulated second (harness/timing/timing.hpp)
};

// Runs `scene` on a fresh engine from `make` at every step of its sweep (and its default step) and
// measures it against both oracles. An engine that cannot run the scene gives a `skipped` baseline.
Baseline make_baseline(const Scene& scene, const EngineFactory& make,
                       const BaselineOptions& options = {});

// "made by `dropcheck bless` with <key>, <build type> \"<flags>\", on commit <commit>": the
// provenance line of a baseline made by this build; `commit` from commit_stamp (build_id.hpp).
std::string provenance(const std::string& commit);

// "<scene>.<engine>.txt"
std::string baseline_file_name(const std::string& scene, const std::string& engine);

}  // namespace dropcheck
