// Identify how an engine's contact bounds friction (harness/core/friction_model.hpp) from slides to
// a stop (harness/oracles/contact_laws.hpp). Along a tangent axis every model decelerates the slip
// by mu*g; at 45 degrees between the engine's tangent axes the models part: a cone still by mu*g,
// a box pyramid by sqrt(2)*mu*g, a sum pyramid by mu*g/sqrt(2). So the ratio of the stop distances
// at 45 and at 0 degrees is 1 for a cone, about 1/sqrt(2) for a box pyramid and about sqrt(2) for a
// sum pyramid (each model's clamp law gives the exact ratio at the scene's step: 1.762376/2.509472
// = 0.7023 and 3.566138/2.509472 = 1.4211 for the shipped slides). A ratio divides out what both
// slides share (a solver that stops either a little short), so it names the model of an engine
// that does not follow the clamp law to the micrometre.
//
// A slide pulled along its floor (an incline: gravity with a part along the floor) is turned the
// same way, its pull to 0 and 45 degrees, and each run measured by how far it has come at the
// scene's end. At 45 degrees the pull meets the cone's grip mu*g, the box pyramid's sqrt(2)*mu*g
// and the sum pyramid's mu*g/sqrt(2), so a ramp steeper than its friction slides different
// distances under each; a box held at 0 degrees (tan < mu) is held at 45 under the cone and the box
// pyramid, and slips under the sum pyramid when tan > mu/sqrt(2): then the distance at 45 degrees
// names the sum pyramid or leaves the other two undecided.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/core/friction_model.hpp"
#include "harness/core/scene.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

// A model fits when its ratio is within this distance of the observed one, relative to the larger
// of its ratio and 1 (a pulled slide that a model holds at 45 degrees has ratio 0 under it). The
// three models' ratios are at least 29 % apart on a launched slide (0.7023, 1, 1.4211) and further
// on the shipped ramp (0, 1, 2.8933); ODE measures 0.70229 at 1/60, the box pyramid's clamp-law
// ratio to 5 digits.
inline constexpr double kFrictionRatioTolerance = 0.05;

// A run that moves at most this far (m) by its end counts as held: a soft or regularised contact
// creeps (MuJoCo 0.94 mm in 3 s on incline_hold, ODE 0.6 mm at 45 degrees on incline_slide).
inline constexpr double kHeldCreep = 0.01;

struct FrictionModelFit {
  FrictionModel model = FrictionModel::cone;
  double ratio = 0.0;        // its clamp laws' distance at 45 degrees over that at 0
  double distance_45 = 0.0;  // m: its clamp law's at 45 degrees
  bool fits = false;         // within kFrictionRatioTolerance of the run
};

struct FrictionIdentification {
  bool pulled = false;                 // an incline: distances at the run's end, not stops
  bool held = false;                   // pulled, and held at 0 degrees under every model
  double distance_0 = 0.0;             // m: the engine's stop distance at 0 degrees
  double distance_45 = 0.0;            // m: and at 45 degrees
  double ratio = 0.0;                  // distance_45 / distance_0
  std::vector<FrictionModelFit> fits;  // cone, box pyramid, sum pyramid
  std::optional<FrictionModel> named;  // the one model that fits, if only one does
  // "ratio 0.70229 (1.762376 m at 45 degrees, 2.509472 m at 0, to the stop): box pyramid; cone
  // 1; box pyramid 0.70229; sum pyramid 1.4211", or on a held ramp "held at 0 degrees; ... m at 45
  // degrees by the run's end: cone or box pyramid (this slide cannot tell them apart); ..."
  std::string sentence() const;
};

// The slide of `scene` (its first launched one, at any angle, else its first pulled one) turned to
// 0 and to 45 degrees between x and z: the two scenes identify_friction compares. Throws
// InputError when the scene has no slide.
struct SlidePair {
  Scene along_axis;
  Scene diagonal;
  bool pulled = false;  // an incline: its pull turned, each run measured to its end
};
SlidePair slide_pair(const Scene& scene);

// From the two distances at the scene's step: the stops (observe_slide) of a launched slide, the
// distances at the run's end of a pulled one.
// `mu`: the pair's coefficient when it is not the scene's (an engine run with each body's own
// coefficient, whose combine rule makes the pair's: identify measures it, pair_friction).
// At step h (the runs').
FrictionIdentification identify_friction(const Scene& scene, double h, double distance_0,
                                         double distance_45,
                                         std::optional<double> mu = std::nullopt);

// The pair's friction coefficient a slide along x shows: the friction impulse over the normal
// impulse of its first kCombineSteps steps (below).
double pair_friction(const Scene& scene, const Trajectory& run);

// Which rule an engine combines two bodies' friction coefficients by. The slide is run with
// each body's own coefficient passed verbatim (Engine::use_body_materials): the cube mu_a = 0.2 on
// a floor of mu_b = 0.8, where the rules' pair values are all apart: product 0.16, minimum 0.2,
// geometric mean 0.4, arithmetic mean 0.5, maximum 0.8. The pair's coefficient is the friction
// impulse over the normal impulse of the cube's first steps, mu = (vx_0 - vx_n)/(vy_n - vy_0 +
// n*g*h): along an axis every model bounds the friction by mu times the normal impulse, and the
// ratio holds whatever the normal impulse is (MuJoCo's pyramid lifts a box launched at 5 m/s
// off its soft floor: a 2.1 m/s normal kick in step 2, and 0.49998 still comes out).
inline constexpr double kCombineBody = 0.2, kCombineFloor = 0.8;
inline constexpr int kCombineSteps = 5;

struct CombineRuleFit {
  const char* rule;  // "product", "minimum", "geometric mean", "arithmetic mean", "maximum"
  double mu = 0.0;   // its pair coefficient
};

struct CombineIdentification {
  double mu_seen = 0.0;              // the pair's coefficient the slide shows
  std::vector<CombineRuleFit> fits;  // every rule
  std::optional<std::string> named;  // the one rule within kFrictionRatioTolerance, if any
  // "mu 0.16 from the first 5 steps (cube 0.2, floor 0.8): product; minimum 0.2, ..."
  std::string sentence() const;
};

// The scene's slide along x with the sliding body's friction kCombineBody and its floor's
// kCombineFloor (the loader refuses two values; only identification builds such a scene). Throws
// InputError when the scene has no slide.
Scene combine_scene(const Scene& scene);

// From a run of combine_scene (every step recorded).
CombineIdentification identify_combine(const Scene& combined, const Trajectory& run);

}  // namespace dropcheck
