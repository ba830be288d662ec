// Contact with exact answers: a box sliding to a stop on a floor and a sphere bouncing on it, each
// as the continuous closed form and as the ideal discrete contact law whose stop step or contact
// step is an integer a check can predict (docs/contact.md). The engines' own deviations (a
// friction pyramid, a soft contact, error reduction added to a rebound) are named against these.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "harness/core/bounce_law.hpp"
#include "harness/core/friction_model.hpp"
#include "harness/core/trajectory.hpp"
#include "harness/scene/scene.hpp"

namespace dropcheck {

// A slide to a stop on a level floor under gravity g, friction mu, from speed v0 along a direction
// at `angle` (rad) from the first tangent axis; only angle 0 and pi/4 are exact for the pyramids
// (at 0 every model is the cone; at pi/4 each axis carries half the slip).
struct SlideStop {
  // Continuous: the deceleration is constant while the body slides.
  double deceleration = 0.0;  // m/s^2 along the slip: mu*g (cone), sqrt(2)*mu*g or mu*g/sqrt(2)
  double stop_time = 0.0;     // s: v0 / deceleration
  double distance = 0.0;      // m: v0^2 / (2*deceleration)
  // The ideal discrete law at step h: per axis v <- max(v - a_i*h, 0), then x += h*v
  // (semi-implicit Euler with the friction impulse clamped at the velocity it cancels).
  std::int64_t stop_step = 0;  // the first step after which the velocity is 0
  double step_distance = 0.0;  // m: the distance travelled by then
};

// Throws std::invalid_argument for v0 < 0, mu <= 0, g <= 0, h <= 0, or a pyramid at an angle other
// than 0 and pi/4.
SlideStop slide_to_stop(double v0, double mu, double g, double h, FrictionModel model,
                        double angle);

// A box resting on a static floor box and launched along it: the slide slide_to_stop predicts.
struct SlideSetup {
  std::size_t body = 0;  // index into Scene::bodies
  double v0 = 0.0;       // m/s, the launch speed (horizontal)
  double angle = 0.0;    // rad from the x axis toward z, folded into [0, pi/4] (x and z symmetric)
  double mu = 0.0;       // the scene's friction
  double g = 0.0;        // m/s^2, gravity straight down
};

// The slides of `scene`: dynamic, unturned boxes whose bottom rests on the top of a static box
// (within 1e-9 m) that spans them, launched with a horizontal velocity, no force or torque on them,
// gravity straight down (-y), contacts on and the scene's friction set. Empty when none.
std::vector<SlideSetup> slide_setups(const Scene& scene);

// What a run shows of a slide: the first recorded step whose horizontal speed is at most
// `stopped_speed`, and the horizontal distance from the start by then (-1 and the last distance
// when it never stops).
struct SlideObservation {
  std::int64_t stop_step = -1;
  double distance = 0.0;  // m
};
SlideObservation observe_slide(const Trajectory& run, const SlideSetup& setup,
                               double stopped_speed);

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

// What a path shows (a law's or a run's): its first impact and the apexes after it.
struct BounceObservation {
  // The step before the first step in which the floor pushed (the velocity rose above what that
  // step's gravity leaves, by over 0.1 % of g*h): the step that ended in the floor, or near it
  // with a speculative contact.
  std::int64_t contact_step = -1;
  double speed_in = 0.0;       // m/s: its downward speed then
  double speed_out = 0.0;      // m/s: its upward speed one step later
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

// A run's path of one bounce: the gaps and vertical velocities of its samples (a run that keeps
// every step, as the checks' runs do).
BouncePath observed_path(const Trajectory& run, const BounceSetup& setup);

}  // namespace dropcheck
