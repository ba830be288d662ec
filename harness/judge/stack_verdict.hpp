// A resting stack judged (harness/oracles/stack.hpp): each body's sink, drift and stillness against
// its engine's stack law, computed in one place for `check` and `report`.
#pragma once

#include <string>
#include <vector>

#include "harness/core/trajectory.hpp"
#include "harness/judge/resting_departure.hpp"
#include "harness/oracles/landing.hpp"
#include "harness/oracles/stack.hpp"

namespace dropcheck {

struct StackBodyVerdict {
  std::size_t body = 0;
  int level = 1;
  StackPrediction predicted;
  double sink = 0.0;   // m: rest height + rest offsets - the final centre height
  double drift = 0.0;  // m: the largest horizontal distance from its start
  StillFigures still;  // over the last StillCriteria::seconds
  // kStackSinkLow*law - bound <= sink <= kStackSink*law + bound, bound StackLaw::sink_bound.
  bool sink_ok = false;
  bool drift_ok = false;  // drift <= StackLaw::drift_bound
  // Speed and range <= StackLaw::still_bound over the last 2 s, judged when that window lies
  // wholly after the column's last landing (a body dropped onto it from rest); else true.
  bool still_judged = false;
  bool still_ok = false;
  bool above_floor = false;  // its centre ends above the floor's top (finite)
  // Some contact of the column has a residual over kUnheldResidual (`limiting`): the solver is not
  // expected to hold the load, a named limit for every body of the column. It waives the sink,
  // drift and stillness bounds, not the floor: a squeezed-out body must still end above it. Or an
  // exact law sinks a box past its face contact (StackPrediction::past_faces): the same limit,
  // the floor waived where the law ends the body below it too.
  bool unheld = false;
  StackPrediction limiting;
  // When it does not hold: the first step it departs (sink, drift or stillness), and how (named in
  // the sentence when it fails, not when a limit passes it).
  RestingDeparture departure;
  bool holds() const { return sink_ok && drift_ok && still_ok; }
  bool passes() const { return holds() || (unheld && above_floor); }
  // "(level 2) sinks 4.083e-06 m (its law: 4.083e-06 m), drift 4.2e-07 m, still: 8.1e-06 m/s,
  // 6.4e-07 m", with what is out of bounds in capitals and, when it does not hold, its first
  // departure.
  std::string sentence() const;
  // "not held, as its solver's sweeps predict: each sweep leaves 0.999 of the error between 1 kg
  // and the 1000 kg on it, 0.99 after a step's sweeps" (when unheld).
  std::string limit_text() const;
};

std::vector<StackBodyVerdict> judge_stack(const Trajectory& run, const StackSetup& setup,
                                          const EngineInfo& info, double h);

}  // namespace dropcheck
