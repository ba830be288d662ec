// A resting stack of boxes on a static floor: the ideal answer (every body at its geometric rest
// height, nothing moving) and what an engine's stack law (harness/core/stack_law.hpp) adds to it,
// per body: the sink of every contact under it, its rest offsets, and whether an iterative solver
// can hold the load at all (docs/contact.md "Stacks").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/scene.hpp"
#include "harness/oracles/landing.hpp"

namespace dropcheck {

// One body of a column, bottom up.
struct StackLevel {
  std::size_t body = 0;      // index into Scene::bodies
  int level = 1;             // 1 on the floor, 2 on the body under it, ...
  double rest_height = 0.0;  // m: floor top + the heights of the bodies under it + its half height
  double mass = 0.0;         // kg
  double load = 0.0;         // kg its lower contact carries: its mass and the masses above it
  double mass_below = 0.0;   // kg: the body it rests on (0: the static floor)
  // 1/kg: what a unit impulse at one corner of its lower contact turns into normal velocity there
  // through the two bodies' rotation, r_z^2/I_xx + r_x^2/I_zz of each body's offset r to the
  // corner (the static floor adds nothing). The corners are those of the overlap of the two faces,
  // which is the smaller face when the body is centred on the one under it (`centred`).
  double corner_turn = 0.0;
  bool centred =
      false;         // its centre over the centre of the body under it (x and z; the floor: yes)
  double gap = 0.0;  // m: its bottom above the top of the body under it at the start
};

// A column of dynamic, unturned boxes over one static floor box, each over the top face of the
// one under it (its centre strictly inside that face), at rest (or dropped from rest onto the body
// under it), no force on them, gravity straight down, contacts on, and no other body sharing a
// member's footprint above the floor (its load or its obstruction would go uncounted). Two or more
// bodies: one body alone is a landing (harness/oracles/landing.hpp).
struct StackSetup {
  std::size_t body = 0;  // its bottom body, which names the column
  std::size_t floor = 0;
  double floor_top = 0.0;          // m
  double g = 0.0;                  // m/s^2, straight down
  double damping_rate = 0.0;       // 1/s, the scene's drag
  std::vector<StackLevel> levels;  // bottom up
};

std::vector<StackSetup> stack_setups(const Scene& scene);

// What the engine's stack law predicts for one level at step h.
struct StackPrediction {
  // m: the steady-state sink of the contacts under it, summed; or, for a law stepped exactly
  // (`exact`), their sink at the run's last step.
  double sink = 0.0;
  bool exact = false;
  // An exact law's own motion from step `from` on: its largest speed (m/s) and height range (m).
  StillFigures still;
  // The step where an exact law sinks a box's centre below the top of the box under it, past the
  // face contact it steps (-1: never); the column's sink there (m).
  std::int64_t past_faces = -1;
  double offset = 0.0;  // m: its rest offsets (EngineInfo::rest_offset per contact)
  // The largest sweep residual of the contacts under it (StackLaw::sweep_residual): over 1/2, the
  // solver cannot hold the load, a named limit.
  double residual = 0.0;
  double load = 0.0, mass = 0.0;  // kg: the load and the body of the contact with that residual
};
// Every level's prediction at once (an exact law steps its column once for all of them).
std::vector<StackPrediction> predict_stack(const StackSetup& setup, const EngineInfo& info,
                                           double h, std::int64_t steps, std::int64_t from = 0);

// `steps`: the run's last step, where an exact law is stepped to; `from`: the first step of the
// window its stillness is taken over.
StackPrediction predict_stack(const StackSetup& setup, std::size_t level, const EngineInfo& info,
                              double h, std::int64_t steps, std::int64_t from = 0);

// A centred column under a relative CFM (harness/core/relative_cfm.hpp; DART's contact), stepped
// from its start: each level's sink below its rest height after `steps` steps. Each contact is
// four corners sharing its impulse X_k equally; its row asks the relative normal velocity of the
// two bodies for the push-out min(erp*d_k/h, max_push) and, regularised, gets
//   v'_k - v'_(k-1) = min(erp*d_k/h, max_push) - cfm*A_k*X_k/4,   X_k >= 0
// with A_k = 1/m_k + 1/m_(k-1) + corner_turn (a corner row's diagonal entry: the corners' turning
// cancels between them in every other row of the contact), v'_k = phi*(v_k - g*h) + (X_k -
// X_(k+1))/m_k (the step's gravity and implicit damping before the impulses, which the damping
// does not scale) and d_k' = d_k - h*(v'_k - v'_(k-1)). A contact is found while d_k >= 0 (a touch
// is one). Throws std::invalid_argument when a level is not centred or the law has no CFM.
struct ColumnPath {
  std::vector<double> sink;         // m, per level: below its rest height after the last step
  std::vector<StillFigures> still;  // per level: its speed and height range from step `from` on
  // The first step that ends with a box's centre below the top of the box under it (-1: none):
  // the four corners of a face contact no longer describe that contact.
  std::int64_t past_faces = -1;
};
ColumnPath relative_cfm_column(const StackSetup& setup, const RelativeCfm& law, double h,
                               std::int64_t steps, std::int64_t from = 0);

// The stack law `info` is judged by: "stepped exactly under constraint force mixing ..." for a
// relative CFM, else its StackLaw's describe.
std::string stack_law_text(const EngineInfo& info);

// The residual past which a solver is not expected to hold a stack.
inline constexpr double kUnheldResidual = 0.5;

}  // namespace dropcheck
