#include "harness/oracles/identify_friction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/oracles/contact_laws.hpp"
#include "harness/oracles/landing.hpp"

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
  const auto launched =
      std::find_if(slides.begin(), slides.end(), [](const SlideSetup& s) { return s.v0 > 0.0; });
  if (launched == slides.end())
    throw InputError(scene.name, 0, "",
                     "has no slide to a stop (a box resting on a static box, launched "
                     "horizontally, with a friction set: docs/contact.md)");
  if (launched->pull != 0.0)
    throw InputError(scene.name, 0, "world.gravity",
                     "pulls the slide along its floor (an incline): the friction model is "
                     "identified from a slide on a level floor, where gravity is straight down");
  return {turned(scene, *launched, 0.0), turned(scene, *launched, std::numbers::pi / 4.0)};
}

FrictionIdentification identify_friction(const Scene& scene, double h, double distance_0,
                                         double distance_45, std::optional<double> mu) {
  SlideSetup s = slide_setups(slide_pair(scene).along_axis).at(0);
  if (mu) s.mu = *mu;
  FrictionIdentification id;
  id.distance_0 = distance_0;
  id.distance_45 = distance_45;
  id.ratio = distance_0 > 0.0 ? distance_45 / distance_0 : NAN;
  int within = 0;
  for (FrictionModel m : kFrictionModels) {
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

Scene combine_scene(const Scene& scene) {
  Scene out = slide_pair(scene).along_axis;
  const SlideSetup s = slide_setups(out).at(0);
  out.bodies[s.body].friction = kCombineBody;
  for (const LandingSetup& l : landing_setups(out))
    if (l.body == s.body) out.bodies[l.floor].friction = kCombineFloor;
  return out;
}

double pair_friction(const Scene& scene, const Trajectory& run) {
  const std::size_t body = slide_setups(scene).at(0).body;
  const double g = -scene.world.gravity.y(), h = run.h;
  if (run.samples() < 2) return NAN;
  const std::size_t n = std::min<std::size_t>(kCombineSteps, run.samples() - 1);
  // Friction impulse over normal impulse (per unit mass) over the first n steps: the x velocity
  // lost, over the y velocity gained beyond gravity's.
  const Vec3 v0 = run.at(0, body).velocity, vn = run.at(n, body).velocity;
  return (v0.x() - vn.x()) / (vn.y() - v0.y() + static_cast<double>(run.recorded[n]) * g * h);
}

CombineIdentification identify_combine(const Scene& combined, const Trajectory& run) {
  CombineIdentification id;
  id.mu_seen = pair_friction(combined, run);
  const double a = kCombineBody, b = kCombineFloor;
  id.fits = {{"product", a * b},
             {"minimum", std::min(a, b)},
             {"geometric mean", std::sqrt(a * b)},
             {"arithmetic mean", (a + b) / 2.0},
             {"maximum", std::max(a, b)}};
  int within = 0;
  for (const CombineRuleFit& f : id.fits)
    if (std::abs(id.mu_seen / f.mu - 1.0) <= kFrictionRatioTolerance) {
      id.named = f.rule;
      ++within;
    }
  if (within != 1) id.named.reset();
  return id;
}

std::string CombineIdentification::sentence() const {
  std::string text = printf_string("mu %.5g from the first %d steps (body %g, floor %g): ", mu_seen,
                                   kCombineSteps, kCombineBody, kCombineFloor);
  text += named ? *named : std::string("NO RULE within 5 %");
  for (const CombineRuleFit& f : fits) text += printf_string("; %s %.5g", f.rule, f.mu);
  return text;
}

}  // namespace dropcheck
