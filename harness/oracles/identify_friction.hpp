// Identify how an engine's contact bounds friction (harness/core/friction_model.hpp) from slides to
// a stop (harness/oracles/contact_laws.hpp). Along a tangent axis every model decelerates the slip
// by mu*g; at 45 degrees between the engine's tangent axes the models part: a cone still by mu*g,
// a box pyramid by sqrt(2)*mu*g, a sum pyramid by mu*g/sqrt(2). So the ratio of the stop distances
// at 45 and at 0 degrees is 1 for a cone, about 1/sqrt(2) for a box pyramid and about sqrt(2) for a
// sum pyramid (each model's clamp law gives the exact ratio at the scene's step: 1.762376/2.509472
// = 0.7023 and 3.566138/2.509472 = 1.4211 for the shipped slides). A ratio divides out what both
// slides share (a solver that stops either a little short), so it names the model of an engine
// that does not follow the clamp law to the micrometre.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/core/friction_model.hpp"
#include "harness/scene/scene.hpp"

namespace dropcheck {

// A model fits when its ratio is within this relative distance of the observed one. The three
// models' ratios are at least 29 % apart (0.7023, 1, 1.4211); ODE measures 0.70229 at 1/60, the box
// pyramid's clamp-law ratio to 5 digits.
inline constexpr double kFrictionRatioTolerance = 0.05;

struct FrictionModelFit {
  FrictionModel model = FrictionModel::cone;
  double ratio = 0.0;  // its clamp laws' distance at 45 degrees over that at 0
};

struct FrictionIdentification {
  double distance_0 = 0.0;             // m: the engine's stop distance at 0 degrees
  double distance_45 = 0.0;            // m: and at 45 degrees
  double ratio = 0.0;                  // distance_45 / distance_0
  std::vector<FrictionModelFit> fits;  // cone, box pyramid, sum pyramid
  std::optional<FrictionModel> named;  // the one model within kFrictionRatioTolerance, if any
  // "ratio 0.7023 (1.762376 m at 45 degrees, 2.509472 m at 0): box pyramid (0.7023); cone 1,
  // sum pyramid 1.421"
  std::string sentence() const;
};

// The slide of `scene` (its first, at any angle) turned to 0 and to 45 degrees between x and z:
// the two scenes identify_friction compares. Throws InputError when the scene has no slide.
struct SlidePair {
  Scene along_axis;
  Scene diagonal;
};
SlidePair slide_pair(const Scene& scene);

// From the two stop distances (observe_slide) at the scene's step.
FrictionIdentification identify_friction(const Scene& scene, double distance_0, double distance_45);

}  // namespace dropcheck
