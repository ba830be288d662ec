// A bounce judged (harness/oracles/contact_laws.hpp): one run's path of a dropped sphere against
// its engine's bounce law, step by step, and that law against the ideal one and the closed form,
// computed in one place for `check` and `report`.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/bounce_law.hpp"
#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"
#include "harness/oracles/contact_laws.hpp"

namespace dropcheck {

struct BounceVerdict {
  BounceLaw law;  // the engine's declared member
  // A replayed solver (harness/core/contact_solver.hpp): its replay is the law instead; empty
  // not_judged unless the scene lies outside the replay's scope (then nothing else is set).
  std::optional<ContactSolver> solver;
  std::string not_judged;
  BounceObservation seen;        // the run's
  BounceObservation predicted;   // its law's
  BounceObservation ideal;       // the ideal law's (kIdealBounce)
  Bounce closed;                 // the continuous closed form
  double worst_gap = 0.0;        // m: the largest |gap - its law's gap| over the run
  std::int64_t worst_step = 0;   // where
  std::int64_t first_step = -1;  // the first step over tolerance::kBouncePath; -1 none
  bool follows = false;          // worst_gap, or else step_gap, <= tolerance::kBouncePath
  // When the path leaves its law's: the largest |gap - the law's step from the run's own state
  // the step before| (bounce_steps), and where. A run that rounds otherwise than the law in double
  // meets a contact decided on a gap within rounding of 0 on the other side, and its path leaves
  // the law's there while every step follows the law: it follows its law.
  double step_gap = -1.0;       // m (-1: not needed, the path follows)
  std::int64_t step_worst = 0;  // where
  double step_speed = 0.0;      // m/s: the largest |v - the law's step| likewise
  // Where the run and its law first decide a step's contact differently (bounce_contact): the step
  // that starts from sample `decided_step`, and the gap each starts it with; -1 when every
  // contact is decided alike.
  std::int64_t decided_step = -1;
  double run_gap_there = 0.0, law_gap_there = 0.0;  // m
  bool follows_ideal = false;  // the run is within that tolerance of the ideal law too
  // When it departs: the neighbouring member of its law whose path it follows instead (the ideal
  // law, the restitution applied twice, the approach read before or after the step's gravity, the
  // body snapped to the surface), and how close; empty if none fits.
  std::string instead;
  double instead_off = 0.0;  // m
  // When none fits: what the engine printed during the run and what that means (engine_said).
  std::string engine_said;
  bool energy_rises = false;  // an apex above the height before it (h0 for the first)
  double law_to_ideal = 0.0;  // m: the largest gap difference between its law and the ideal's
  // The members of its law that move its path off the ideal one (each alone, the other removed):
  // "push-out 0.2*depth/h capped at 0.3 m/s", "restitution of the step-start approach speed above
  // 1 m/s".
  std::vector<std::string> causes;
  // "hits at step 27 at 4.41 m/s, leaves at 2.205 m/s, apexes 0.2378, 0.05942, 0.01482 m; its law
  // (restitution of ...): the same to 2e-08 m; the ideal law's apexes ...; continuous ...", with
  // " DEPARTS from its law at step N by X m" when it does not follow.
  std::string sentence() const;
  // "step 56 starts 6e-16 m into the floor in the law and 1.8e-07 m above it in the run, so the
  // two decide its contact on either side", or the rounding alone.
  std::string parting_text() const;
};

BounceVerdict judge_bounce(const Trajectory& run, const BounceSetup& setup, const BounceLaw& law,
                           double h);

// Against the engine's own law: its bounce law, or the replay of its solver (info.contact_solver)
// when the harness replays it.
BounceVerdict judge_bounce(const Trajectory& run, const Scene& scene, const BounceSetup& setup,
                           const EngineInfo& info, double h);

// "0.2378, 0.05942, 0.01482 m" or "none".
std::string apex_text(const std::vector<double>& apexes);

}  // namespace dropcheck
