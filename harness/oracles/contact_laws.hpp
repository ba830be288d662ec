// Contact with exact answers: a box sliding to a stop on a floor and a sphere bouncing on it, each
// as the continuous closed form and as the ideal discrete contact law whose stop step or contact
// step is an integer a check can predict (docs/contact.md). The engines' own deviations (a
// friction pyramid, a soft contact, error reduction added to a rebound) are named against these.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "harness/core/bounce_law.hpp"
#include "harness/core/friction_model.hpp"
#include "harness/core/law.hpp"
#include "harness/core/relative_cfm.hpp"
#include "harness/core/scene.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

// What every contact law here assumes: contacts on, gravity with a part into a level floor (-y),
// nothing turning. A bounce and a stack also need gravity straight down (level_gravity).
bool floor_contact(const Scene& scene);
bool level_gravity(const Scene& scene);

// A slide on a floor under friction mu, with gravity g into the floor and `pull` (m/s^2) along it:
// a level floor has no pull, an incline of angle theta is a floor under gravity tilted by theta
// (g = g0*cos(theta) into it, pull = g0*sin(theta) down the slope). The slip and the pull are
// collinear, along a direction at `angle` (rad) from the first tangent axis; only angle 0 and pi/4
// are exact for the pyramids (at 0 every model is the cone; at pi/4 each axis carries half).
//
// Along the slip the friction model grips at most grip = mu_eff*g per unit mass: mu*g for the cone
// and along an axis; at pi/4 the box pyramid bounds each axis by mu*g (sqrt(2)*mu*g along the
// slip) and the sum pyramid shares mu*g between them (mu*g/sqrt(2)).
double slide_grip(double mu, double g, FrictionModel model, double angle);

// The model's slide has an exact answer at `angle` (folded into [0, pi/4]): the cone at any angle,
// the pyramids at 0 and pi/4 only.
bool exact_slide_angle(FrictionModel model, double angle);

struct SlideStop {
  // Continuous, while the body slides on from v0 >= 0 (along the slip, pull signed along it).
  double deceleration = 0.0;  // m/s^2: grip - pull (negative: the pull wins and it speeds up)
  bool stops = false;         // it comes to rest and stays: |pull| <= grip and v0 stops
  double stop_time = 0.0;     // s: v0/deceleration (0 for a body that never moves)
  double distance = 0.0;      // m: v0^2/(2*deceleration)
  // The ideal discrete law at step h (slide_path): the stop step N = ceil(v0/(deceleration*h))
  // and the distance h*((N - 1)*v0 - deceleration*h*(N - 1)*N/2) by then; -1 when it never stops.
  std::int64_t stop_step = -1;
  double step_distance = 0.0;
};

// Throws std::invalid_argument for v0 < 0, mu <= 0, g <= 0, h <= 0, or a pyramid at an angle other
// than 0 and pi/4.
SlideStop slide_to_stop(double v0, double mu, double g, double h, FrictionModel model, double angle,
                        double pull = 0.0);

// The continuous distance along the slip after t seconds of a slide from v0 >= 0 with `grip` and
// `pull` (as above): it decelerates at grip - pull to a stop, then stays while |pull| <= grip or
// slides toward the pull at |pull| - grip. Negative once it has slid back past its start.
double slide_distance_continuous(double v0, double pull, double grip, double t);

// A box resting on a static floor box and sliding along it: the slide slide_to_stop predicts.
struct SlideSetup {
  std::size_t body = 0;  // index into Scene::bodies
  double v0 = 0.0;       // m/s, the launch speed along the floor
  Vec3 direction;      // the slip's unit direction in the x-z plane (the launch's, else the pull's)
  double angle = 0.0;  // rad from the x axis toward z, folded into [0, pi/4] (x and z symmetric)
  double mu = 0.0;     // the scene's friction
  double g = 0.0;      // m/s^2, gravity into the floor (-y)
  double pull = 0.0;   // m/s^2, gravity along the floor, signed along `direction`
};

// The slides of `scene`: dynamic, unturned boxes whose bottom rests on the top of a static box
// (within 1e-9 m) that spans them, launched along the floor or pulled along it by a gravity with an
// x-z part collinear with the launch, no force or torque on them, no other body on or under them
// (landing_exclusions: the normal force would not be m*g), no damping, contacts on and the scene's
// friction set, and the slide stays over its floor for the scene's duration (the ideal discrete
// slide of every model at the scene's step, 1 % longer). Empty when none.
std::vector<SlideSetup> slide_setups(const Scene& scene);

// A slide's path a step at a time: after step n = 0..steps, s[n] (m, along the slip from the
// start), v[n] (m/s along it) and off[n] (m, the distance across it and up or down from its height
// after step 1: 0 for a law).
struct SlidePath {
  std::vector<double> s, v, off;
};

// The ideal discrete law of `model`: per step v_free = v + pull*h; the friction impulse cancels the
// slip when it can (|v_free| <= grip*h gives v = 0) and otherwise takes grip*h off it; x += h*v
// with the new v, or with the step-start v for an engine whose position update is explicit
// (Chipmunk: by step n it has moved h*(v0 - v_n) further, h*v0 for a slide that has stopped).
// Under relative constraint force mixing `soft` (DART: harness/core/relative_cfm.hpp) the grip of
// each step is scaled by that step's normal impulse, a stopping step leaves cfm/(1 + cfm) of the
// slip, and off[n] is the sink since step 1. With `friction_after_position` (a neighbour no
// shipped engine declares: an engine that moves its bodies before it resolves their contacts) the
// position moves with v_free, the speed before the friction.
SlidePath slide_path(const SlideSetup& setup, FrictionModel model, double h, std::int64_t steps,
                     PositionUpdate position = PositionUpdate::SemiImplicit,
                     const RelativeCfm& soft = {}, bool friction_after_position = false);

// The law one step ahead of a path (a run's): step n + 1 of the result is the law's step from
// `from`'s state after step n. A run that rounds differently from the law in double (a float
// engine) can leave the law's whole path where a contact decision lies within rounding, and still
// follow the law at every step.
SlidePath slide_steps(const SlideSetup& setup, FrictionModel model, double h, const SlidePath& from,
                      PositionUpdate position = PositionUpdate::SemiImplicit,
                      const RelativeCfm& soft = {});

// The path of the slide's body from its state after each step 0, 1, ... (a run's, a replay's).
SlidePath slide_path_of(std::span<const BodyState> states, const SlideSetup& setup);

// A run's path of one slide (a run that keeps every step, as the checks' runs do).
SlidePath observed_slide_path(const Trajectory& run, const SlideSetup& setup);

// What a path shows: the first step from which its speed stays at most `stopped_speed` and its
// position within `settled` of where it ends (0 for a body that never moves; -1 when it is still
// moving at the end), and the distance along the slip by then (by the end when it never stops).
// The position counts as well as the speed: a run that reports no speed while it creeps has not
// stopped.
struct SlideObservation {
  std::int64_t stop_step = -1;
  double distance = 0.0;  // m
};
SlideObservation observe_slide(const SlidePath& path, double stopped_speed, double settled);

// A sphere's fall and bounces on a level floor under a bounce law (harness/core/bounce_law.hpp),
// from rest with its lowest point h0 above the floor: after step n = 0..steps, gap[n] (m, the
// lowest point above the floor; negative while it penetrates) and v[n] (m/s, up positive).
struct BouncePath {
  std::vector<double> gap, v;
};
// `size` is the smaller bounding-box half diagonal of the sphere and its floor (m), which scales
// the law's contact_distance_per_size.
BouncePath bounce_path(const BounceLaw& law, double h0, double e, double g, double h,
                       std::int64_t steps, double size = 0.0);

// Whether a step that starts with the sphere's lowest point `gap` above the floor (negative: in
// it) meets a contact under `law` (its contact distance, and a touch when `touching`).
bool bounce_contact(const BounceLaw& law, double gap, double size = 0.0);

// The law one step ahead of a path (a run's), as slide_steps.
BouncePath bounce_steps(const BounceLaw& law, const BouncePath& from, double e, double g, double h,
                        double size = 0.0);

// What a path shows (a law's or a run's): its first impact and the apexes after it.
struct BounceObservation {
  // The step before the first step in which the floor pushed (the velocity rose above what that
  // step's gravity leaves, by over 0.1 % of g*h): the step that ended in the floor, or near it
  // with a speculative contact.
  std::int64_t contact_step = -1;
  double speed_in = 0.0;  // m/s: its downward speed then
  // m/s: its speed after the last of the impact's consecutive steps in which the floor pushed (one
  // step later for a rigid contact; a soft contact pushes over several steps)
  double speed_out = 0.0;
  std::vector<double> apexes;  // m: the highest gap of each flight after an impact
};
// gap[i] and v[i] are those after step i, under gravity g at step h; at most `bounces` apexes. An
// apex is the last gap before the velocity turns from up to down.
BounceObservation observe_bounce(const std::vector<double>& gap, const std::vector<double>& v,
                                 double g, double h, int bounces = 3);

// A sphere dropped from rest with its lowest point h0 above a level floor, restitution e.
struct Bounce {
  // Continuous: each impact returns e times the impact speed.
  double impact_speed = 0.0;    // m/s: sqrt(2*g*h0)
  std::vector<double> apexes;   // m above the floor after bounce n = 1, 2, ...: e^(2n)*h0
  std::vector<double> flights;  // s, the flight after bounce n: 2*e^n*sqrt(2*h0/g)
  double time_to_rest = 0.0;    // s: sqrt(2*h0/g)*(1 + e)/(1 - e) (infinite for e = 1)
  // The ideal discrete law at step h (kIdealBounce): semi-implicit free fall until the step that
  // ends in the floor, the contact step; the next step leaves at e times the speed it ended with,
  // from where the sphere is; then free flight again.
  std::int64_t contact_step = 0;  // the step of the first impact
  double step_speed_in = 0.0;     // m/s: g*h*contact_step
  double step_speed_out = 0.0;    // m/s: e*step_speed_in
  double step_apex = 0.0;         // m above the floor: the highest position after that impact
};

// `bounces` continuous apexes and flights. Throws std::invalid_argument for h0 <= 0, g <= 0,
// h <= 0, or e outside [0, 1].
Bounce bounce(double h0, double e, double g, double h, int bounces = 3);

// A sphere resting in the air over a static floor box, dropped: the bounce `bounce` predicts.
struct BounceSetup {
  std::size_t body = 0;    // index into Scene::bodies
  double h0 = 0.0;         // m: its lowest point above the floor's top
  double e = 0.0;          // the scene's restitution
  double g = 0.0;          // m/s^2, gravity straight down
  double radius = 0.0;     // m
  double floor_top = 0.0;  // m
  double size = 0.0;       // m: the smaller bounding-box half diagonal of the sphere and its floor
};

// The bounces of `scene`: dynamic spheres at rest above a static box that holds them, neither on
// nor under another dynamic body (landing_exclusions), no force on them, gravity straight down
// (-y), no damping, contacts on and the scene's restitution set.
std::vector<BounceSetup> bounce_setups(const Scene& scene);

// The path of the bounce's sphere from its state after each step 0, 1, ... (a run's, a replay's).
BouncePath bounce_path_of(std::span<const BodyState> states, const BounceSetup& setup);

// A run's path of one bounce: the gaps and vertical velocities of its samples (a run that keeps
// every step, as the checks' runs do).
BouncePath observed_path(const Trajectory& run, const BounceSetup& setup);

}  // namespace dropcheck
