#include "harness/oracles/identify_friction.hpp"

#include <cmath>
#include <numbers>

#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/oracles/contact_laws.hpp"

namespace dropcheck {
namespace {

// The scene with its sliding body launched at the same speed at `angle` from x toward z.
Scene turned(const Scene& scene, const SlideSetup& s, double angle) {
  Scene out = scene;
  Body& b = out.bodies[s.body];
  b.velocity = Vec3(s.v0 * std::cos(angle), 0.0, s.v0 * std::sin(angle));
  return out;
}

}  // namespace

SlidePair slide_pair(const Scene& scene) {
  const std::vector<SlideSetup> slides = slide_setups(scene);
  if (slides.empty())
    throw InputError(scene.name, 0, "",
                     "has no slide to a stop (a box resting on a static box, launched "
                     "horizontally, with a friction set: docs/contact.md)");
  return {turned(scene, slides[0], 0.0), turned(scene, slides[0], std::numbers::pi / 4.0)};
}

FrictionIdentification identify_friction(const Scene& scene, double distance_0,
                                         double distance_45) {
  const SlideSetup s = slide_setups(slide_pair(scene).along_axis).at(0);
  const double h = scene.timestep.seconds;
  FrictionIdentification id;
  id.distance_0 = distance_0;
  id.distance_45 = distance_45;
  id.ratio = distance_0 > 0.0 ? distance_45 / distance_0 : NAN;
  int within = 0;
  for (FrictionModel m :
       {FrictionModel::cone, FrictionModel::box_pyramid, FrictionModel::sum_pyramid}) {
    const double d0 = slide_to_stop(s.v0, s.mu, s.g, h, m, 0.0).step_distance;
    const double d45 = slide_to_stop(s.v0, s.mu, s.g, h, m, std::numbers::pi / 4.0).step_distance;
    id.fits.push_back({m, d45 / d0});
    if (std::abs(id.ratio / (d45 / d0) - 1.0) <= kFrictionRatioTolerance) {
      id.named = m;
      ++within;
    }
  }
  if (within != 1) id.named.reset();
  return id;
}

std::string FrictionIdentification::sentence() const {
  std::string text = printf_string("ratio %.5g (%.7g m at 45 degrees, %.7g m at 0): ", ratio,
                                   distance_45, distance_0);
  text += named ? std::string(to_string(*named)) : std::string("NO MODEL within 5 %");
  for (const FrictionModelFit& f : fits)
    text += printf_string("; %s %.5g", to_string(f.model), f.ratio);
  return text;
}

}  // namespace dropcheck
