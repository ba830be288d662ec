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
#include <optional>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

// One dynamic body above a static floor box, and what the continuous model expects of its landing.
struct LandingSetup {
  std::size_t body = 0;       // index into Scene::bodies
  std::size_t floor = 0;      // static body whose top is under the body's centre
  double floor_top = 0.0;     // m: floor centre y + floor half extent y
  double floor_bottom = 0.0;  // m: floor centre y - floor half extent y (geometric, never shifted)
  double half_height = 0.0;   // m: the body's half extent along y (bottom = centre - this)
  double rest_height = 0.0;   // m: floor_top + body half extent y (centre of a resting body)
  double contact_time = 0.0;  // s: continuous model, bottom reaches floor_top; NaN if never
  double weight = 0.0;        // N: m*|g|, what the floor carries at rest
};

// Whether a body sat still over the last `seconds` of a run (to the end).
struct StillCriteria {
  double seconds = 2.0;     // window at the end of the run
  double max_speed = 1e-3;  // m/s: largest |v| allowed in the window
  double max_range = 1e-3;  // m: largest (max - min) of any position component in the window
};

// The largest |v| and the largest range of any position component (max - min) of `body` over the
// samples from step `from` on.
struct StillFigures {
  double speed = 0.0;  // m/s
  double range = 0.0;  // m
};
StillFigures still_figures(const Trajectory& run, std::size_t body, std::int64_t from);

// What one run shows of a LandingSetup.
struct LandingObservation {
  std::int64_t first_contact_step = -1;  // first recorded step with bottom <= floor top; -1 never
  double first_contact_time = 0.0;       // s: first_contact_step * h (NaN if never)
  double deepest = 0.0;                  // m: lowest centre minus rest height (< 0: penetration)
  double rebound = 0.0;                  // m: highest centre from first contact on, minus rest
  double rest_offset = 0.0;              // m: final centre minus rest height
  double still_speed = 0.0;              // m/s: largest |v| in the still window
  double still_range = 0.0;              // m: largest position range in the still window
  bool still_judged = false;             // the still window lies wholly after first contact
  double after_contact = 0.0;            // s: from first contact to the run's end (NaN if never)
  bool still = false;                    // still_judged, and within the criteria
};

// A dynamic body over a floor that the single-body oracle does not judge: another dynamic body
// shares its x-z footprint (rectangles overlap) above the floor, so it lands on that body or that
// body lands on it.
struct LandingExclusion {
  std::size_t body = 0;   // index into Scene::bodies
  std::size_t other = 0;  // the dynamic body below or above it, or a static one below it
  bool on_other = false;  // true: it lands on `other` (other is below); false: other lands on it
  // "'heavy' not judged: lands on dynamic body 'light' (the landing oracle covers one body over
  // a static floor)".
  std::string sentence(const Scene& scene) const;
};

// Every dynamic body with a static box under its centre (the highest one whose top is below the
// body's bottom and whose x-z footprint contains the body's x-z position), in body order; stacked
// bodies included (the geometry of every fall, not who is judged).
std::vector<LandingSetup> landing_setups(const Scene& scene);

// The bodies of landing_setups that share their x-z footprint with another dynamic body above the
// floor top, or with a static body other than their floor below them (a static sphere is no floor
// but is in the way), in body order (the nearest body below it is named, else the nearest above).
std::vector<LandingExclusion> landing_exclusions(const Scene& scene);

// landing_setups without landing_exclusions and without the bouncing spheres and the slides
// (bounce_setups, slide_setups: judged by their own contact laws), none at all under gravity with
// a part along the floor (a landing body slides on), as one engine meets the floor:
// an engine whose resting surface sits above the geometry (Box2D's 0.01 m skin) touches it there,
// so contact means reaching the floor top plus max(0, rest_offset + rest_tolerance). The one place
// the bodies to judge are chosen and that shift is made (check and report).
std::vector<LandingSetup> engine_landing_setups(const Scene& scene, const EngineInfo& info);

// Tunnelling of the engine's own discrete law (contacts ignored): at the first step whose centre
// is at or below the floor slab's top widened by the half height (floor top + half height), is it
// already below the slab's bottom widened the same way (floor bottom - half height)? Then no
// end-of-step position ever overlaps the floor, and an engine that tests overlap only at step ends
// (no continuous collision) cannot see it.
struct Tunnelling {
  bool tunnels = false;          // the law jumps over the widened slab in one step
  std::int64_t step = -1;        // first step at or below the widened slab's top; -1 never
  double travel = 0.0;           // m: distance the centre moves over that step
  double floor_thickness = 0.0;  // m: floor top - floor bottom (geometric)
  double height = 0.0;           // m: the body's full height (2 * half_height)
  // "tunnels: it travels 3.33 m per step at contact, more than the floor (0.01 m) plus its
  // height (1 m)".
  std::string sentence() const;
};

// Tunnelling of predict_discrete(law, scene, h) for `setup`'s body over its (geometric) floor.
Tunnelling discrete_tunnelling(Law law, const Scene& scene, double h, const LandingSetup& setup);

// Whether the run ends with the body wholly below its floor (centre below floor bottom - half
// height): it went through.
bool ends_below_floor(const Trajectory& run, const LandingSetup& setup);

// How a run that ends below the floor is judged (check and report alike): `limit` when the law
// tunnels and the engine has no continuous collision (passed, the cause named); `fault` when the
// law tunnels and the engine declares continuous collision yet went through; `none` otherwise
// (judge the landing as usual).
enum class TunnelVerdict { none, limit, fault };
TunnelVerdict judge_tunnelling(const Tunnelling& law, const EngineInfo& info, const Trajectory& run,
                               const LandingSetup& setup);

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

// The landing of an engine whose contact is regularised with a capped push-out
// (EngineInfo::relative_cfm with a finite max_push: DART), step by step: the body falls as the
// engine's free-flight law until its first step at or below the rest height, then each step that
// starts in the floor (depth d >= 0) is relative_cfm's contact_step from the law's free velocity
// (gravity and damping), and x += h*v. Such a body stops about |v|*h deep and climbs out at the
// cap, for minutes: the path, not a rest height, is what a run must follow.
struct ClimbPath {
  std::vector<double> y;  // m: centre height after steps 0..steps
  double climb = 0.0;     // m/s: the normal velocity after the last step
  // Set for a path the engine's contact solver replays (replayed_landing_path), not a climb: what
  // it replays.
  std::string replayed;
};

// The climb path of `setup`'s body at step h, for an engine that declares a capped push-out and a
// semi-implicit member with its damping before the position update, on a body no force pushes;
// nullopt otherwise (the landing is judged by the declared rest offset).
std::optional<ClimbPath> climb_path(const EngineInfo& info, const Scene& scene, double h,
                                    const LandingSetup& setup);

// The landing of an engine whose contact force law the harness steps (Simbody's compliant contact,
// harness/oracles/replayed_contact.hpp): that law's heights, every step; nullopt for other
// engines or a landing outside the replay's scope.
std::optional<ClimbPath> replayed_landing_path(const EngineInfo& info, const Scene& scene, double h,
                                               const LandingSetup& setup);

// The largest |y - path| of the run's body over its samples.
double off_climb(const Trajectory& run, const LandingSetup& setup, const ClimbPath& path);

// Landing figures of one run (any status: a failed run is analysed up to its last sample).
LandingObservation observe_landing(const Trajectory& run, const LandingSetup& setup,
                                   const StillCriteria& still = {});

}  // namespace dropcheck
