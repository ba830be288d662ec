// Where a body that should come to rest (a landing, a level of a stack) first leaves what its law
// expects of it, which quantity, and what the run does instead: the cause a failing landing or
// stack verdict names (`check`, the report). Computed from the run alone, step by step.
#pragma once

#include <cstdint>
#include <string>

#include "harness/core/law.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

struct RestingDeparture {
  std::int64_t step = -1;  // the first departing step; -1: none
  std::string quantity;    // "rebound", "rest height", "drift", "stillness", "path"
  std::string cause;       // what the run does there, with the figure that shows it
  // "first departs at step 130 (rebound): it leaves the floor at 2.1 m/s after meeting it at
  // 7.3 m/s, a restitution of 0.29 where its law comes to rest"; "" when none.
  std::string sentence() const;
};

// The earlier of two departures (either may be none).
RestingDeparture earlier(const RestingDeparture& a, const RestingDeparture& b);

// The first step after `contact` at which `body` is more than `limit` above `rest_y`: a rebound,
// with the speed it meets the floor at and leaves it with.
RestingDeparture rebound_departure(const Trajectory& run, std::size_t body, std::int64_t contact,
                                   double rest_y, double limit);

// The first step of the run's last stretch in which `body`'s height stays more than `tolerance`
// from `expected_y`: resting too low (a soft contact's sag, with the spring that would hold the
// weight m*g there) or too high (pushed out beyond its rest). A body resting `level` times
// `one_step_fall` low (its law's move in one step from rest, to 1e-3 of it; `level` of a stack, 1
// on the floor) has its contacts resolved after the position update: each step it falls that far
// before the push-out returns the depth the step started with, and so does each body under it.
RestingDeparture rest_departure(const Trajectory& run, std::size_t body, double expected_y,
                                double tolerance, double weight, double one_step_fall = 0.0,
                                int level = 1);

// m: how far `law` moves a body in one step from rest under a gravity of `g` (m/s^2, straight down)
// with the per-step drag factor `phi` (g*h^2*phi for semi-implicit Euler; 0 for an explicit
// position update): what a contact resolved after the position update leaves a resting body below
// its rest, per level of a stack (rest_departure's one_step_fall).
double one_step_fall(Law law, double phi, double h, double g);

// The first step at which `body` is more than `bound` from its start across the floor (x-z).
RestingDeparture drift_departure(const Trajectory& run, std::size_t body, double bound);

// The first step from `from` on at which `body` moves faster than `max_speed`, or has spread over
// more than `max_range` along an axis since `from`: an oscillation about its rest (with its
// reversals) or a creep.
RestingDeparture stillness_departure(const Trajectory& run, std::size_t body, std::int64_t from,
                                     double max_speed, double max_range);

// The first step at which `body`'s height is more than `tolerance` from `path` (its law's height at
// every step).
RestingDeparture path_departure(const Trajectory& run, std::size_t body,
                                const std::vector<double>& path, double tolerance);

}  // namespace dropcheck
