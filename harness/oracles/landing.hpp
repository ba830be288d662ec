// Landing on a static floor, engine-neutral: what the continuous model and the geometry expect
// (first-contact time, rest height) and what a run shows (first contact, rebound, resting offset,
// stillness). docs/engines.md section 5 has each engine's resting offset.
//
// Vertical model of a dynamic body before contact (y up, per unit mass):
//   dv/dt = a - k*v,  a = g_y + F_y/m  (gravity plus the body's constant forces; springs ignored)
// The body's bottom touches the floor when its centre reaches the geometric rest height
//   y_rest = floor top + half extent along y.
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

// One dynamic body above a static floor box, and what the continuous model expects of its landing.
struct LandingSetup {
  std::size_t body = 0;       // index into Scene::bodies
  std::size_t floor = 0;      // static body whose top is under the body's centre
  double floor_top = 0.0;     // m: floor centre y + floor half extent y
  double half_height = 0.0;   // m: the body's half extent along y (bottom = centre - this)
  double rest_height = 0.0;   // m: floor_top + body half extent y (centre of a resting body)
  double contact_time = 0.0;  // s: continuous model, bottom reaches floor_top; NaN if never
};

// Whether a body sat still over the last `seconds` of a run (to the end).
struct StillCriteria {
  double seconds = 2.0;     // window at the end of the run
  double max_speed = 1e-3;  // m/s: largest |v| allowed in the window
  double max_range = 1e-3;  // m: largest (max - min) of any position component in the window
};

// What one run shows of a LandingSetup.
struct LandingObservation {
  std::int64_t first_contact_step = -1;  // first recorded step with bottom <= floor top; -1 never
  double first_contact_time = 0.0;       // s: first_contact_step * h (NaN if never)
  double deepest = 0.0;                  // m: lowest centre minus rest height (< 0: penetration)
  double rebound = 0.0;                  // m: highest centre from first contact on, minus rest
  double rest_offset = 0.0;              // m: final centre minus rest height
  double still_speed = 0.0;              // m/s: largest |v| in the still window
  double still_range = 0.0;              // m: largest position range in the still window
  bool still = false;                    // window entirely after first contact, within criteria
};

// Every dynamic body with a static box under its centre (the highest one whose top is below the
// body's bottom and whose x-z footprint contains the body's x-z position), in body order.
std::vector<LandingSetup> landing_setups(const Scene& scene);

// landing_setups as one engine meets the floor: an engine whose resting surface sits above the
// geometry (Box2D's 0.01 m skin) touches it there, so contact means reaching the floor top plus
// max(0, rest_offset + rest_tolerance). The one place that shift is made (check and report).
std::vector<LandingSetup> engine_landing_setups(const Scene& scene, const EngineInfo& info);

// Centre height y(t) of the continuous model from y0, v0 (m, m/s) with acceleration a (m/s^2) and
// damping rate k (1/s).
double height_continuous(double y0, double v0, double a, double k, double t);

// First t > 0 with height_continuous(...) = target, for y0 > target; NaN when it never gets there.
double contact_time_continuous(double y0, double v0, double a, double k, double target);

// First recorded step of `run` whose body bottom is at or below the floor top; -1 when none.
std::int64_t first_contact_step(const Trajectory& run, const LandingSetup& setup);

// First-contact step of the engine's own discrete law: predict_discrete(law, scene, h) (contacts
// ignored) until the bottom is at or below the floor top; -1 when not within the scene's duration.
std::int64_t discrete_contact_step(Law law, const Scene& scene, double h,
                                   const LandingSetup& setup);

// Landing figures of one run (any status: a failed run is analysed up to its last sample).
LandingObservation observe_landing(const Trajectory& run, const LandingSetup& setup,
                                   const StillCriteria& still = {});

}  // namespace dropcheck
