// A tumbling landing judged step by step against the engine's declared turned-box contact law
// (harness/core/turned_contact.hpp), computed in one place for `check` and `report`: each step of
// the run taken from the run's own state the step before (turned_contact_step), so that a float
// engine's rounding, which a tumble amplifies, never accumulates into the verdict.
#pragma once

#include <cstdint>
#include <string>

#include "harness/core/trajectory.hpp"

namespace dropcheck {

// How far one step of a run lands from the law's nearest candidate, each quantity worst over the
// bodies: |dx| (m), |dv| (m/s), the geodesic angle between orientations (rad), |dw| (rad/s).
struct TurnedResidual {
  double position = 0.0, velocity = 0.0, angle = 0.0, spin = 0.0;
  // The largest of the four over its tolerance (<= 1: within).
  double ratio(const TurnedResidual& tolerance) const;
};

struct TurnedVerdict {
  std::string not_judged;            // why the law was not applied (empty when judged)
  std::int64_t steps = 0;            // steps judged (every step of the run)
  std::int64_t contact_steps = 0;    // of them, steps that start with a corner in contact
  std::int64_t undecided_steps = 0;  // steps with a corner within rounding of the face
  // The step tolerance (tolerance::kTurnedStepUlps of each quantity's size) at the first
  // departure, else at the step closest to it.
  TurnedResidual tolerance;
  TurnedResidual worst;               // the largest of each over the run
  std::int64_t worst_step = -1;       // the step with the largest ratio
  std::int64_t first_departure = -1;  // first step over the tolerance; -1 none
  std::string departure_quantity;     // "position", "velocity", "orientation", "angular velocity"
  TurnedResidual at_departure;
  bool follows() const { return not_judged.empty() && first_departure < 0; }
  // "follows its turned-box contact law (one impulse at the mean of the corners in the floor) at
  // every step ...: 120 steps, 77 starting in contact, ...; worst |dx| 2.2e-16 m, ..." or "DEPARTS
  // at step 42: angular velocity off, ...".
  std::string sentence() const;
};

// `run` (which must keep every step) against `info`'s declared turned-box contact law at h.
TurnedVerdict judge_turned_contact(const Scene& scene, const EngineInfo& info,
                                   const Trajectory& run);

}  // namespace dropcheck
