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

// The scene with its sliding body's launch, and its pull along the floor, turned to `angle` from
// x toward z (the same speed and the same pull).
Scene turned(const Scene& scene, const SlideSetup& s, double angle) {
  Scene out = scene;
  const Vec3 along(std::cos(angle), 0.0, std::sin(angle));
  out.bodies[s.body].velocity = s.v0 * along;
  out.world.gravity = Vec3(0.0, scene.world.gravity.y(), 0.0) + s.pull * along;  // uphill: < 0
  return out;
}

// Model m's clamp-law distances of `pair` at 0 and 45 degrees (mu replaced when given): to the
// stop of a launched slide, to the run's end (`steps`) of a pulled one.
std::pair<double, double> law_distances(const SlidePair& pair, FrictionModel m, double h,
                                        std::int64_t steps, std::optional<double> mu) {
  double d[2];
  const Scene* scenes[2] = {&pair.along_axis, &pair.diagonal};
  for (int i = 0; i < 2; ++i) {
    SlideSetup s = slide_setups(*scenes[i]).at(0);
    if (mu) s.mu = *mu;
    d[i] = pair.pulled ? slide_path(s, m, h, steps).s.back()
                       : slide_to_stop(s.v0, s.mu, s.g, h, m, s.angle).step_distance;
  }
  return {d[0], d[1]};
}

}  // namespace

SlidePair slide_pair(const Scene& scene) {
  const std::vector<SlideSetup> slides = slide_setups(scene);
  if (slides.empty())
    throw InputError(scene.name, 0, "",
                     "has no slide (a box resting on a static box, launched along it or pulled "
                     "along it by gravity, with a friction set: docs/contact.md)");
  const auto launched = std::find_if(slides.begin(), slides.end(), [](const SlideSetup& s) {
    return s.v0 > 0.0 && s.pull == 0.0;
  });
  const SlideSetup& s = launched != slides.end() ? *launched : slides.front();
  return {turned(scene, s, 0.0), turned(scene, s, std::numbers::pi / 4.0), s.pull != 0.0};
}

FrictionIdentification identify_friction(const Scene& scene, double h, double distance_0,
                                         double distance_45, std::optional<double> mu) {
  const SlidePair pair = slide_pair(scene);
  const std::int64_t steps = step_count(pair.along_axis, h);
  FrictionIdentification id;
  id.pulled = pair.pulled;
  id.distance_0 = distance_0;
  id.distance_45 = distance_45;
  id.ratio = distance_0 > 0.0 ? distance_45 / distance_0 : NAN;
  std::vector<std::pair<double, double>> laws;
  double spread = 0.0;  // the largest clamp-law distance at 45 degrees
  for (FrictionModel m : kFrictionModels) {
    laws.push_back(law_distances(pair, m, h, steps, mu));
    spread = std::max(spread, laws.back().second);
  }
  // Held at 0 degrees under every model, and by the run within a creep: the distance at 45
  // degrees alone, within the tolerance of the largest or a creep; else the ratio, which divides
  // out what both slides share.
  id.held = pair.pulled && laws.front().first == 0.0;
  const double held_tolerance = std::max(kFrictionRatioTolerance * spread, kHeldCreep);
  int within = 0;
  for (std::size_t i = 0; i < laws.size(); ++i) {
    const auto [d0, d45] = laws[i];
    const bool fits =
        id.held
            ? std::abs(distance_0) <= kHeldCreep && std::abs(distance_45 - d45) <= held_tolerance
            : std::abs(id.ratio - d45 / d0) <= kFrictionRatioTolerance * std::max(d45 / d0, 1.0);
    id.fits.push_back({kFrictionModels[i], d45 / d0, d45, fits});
    if (fits) {
      id.named = kFrictionModels[i];
      ++within;
    }
  }
  if (within != 1) id.named.reset();
  return id;
}

std::string FrictionIdentification::sentence() const {
  const char* what = pulled ? "by the run's end" : "to the stop";
  std::string text =
      held ? printf_string("held at 0 degrees; %.7g m at 45 degrees %s: ", distance_45, what)
           : printf_string("ratio %.5g (%.7g m at 45 degrees, %.7g m at 0, %s): ", ratio,
                           distance_45, distance_0, what);
  std::string fitting;
  for (const FrictionModelFit& f : fits)
    if (f.fits) fitting += (fitting.empty() ? "" : " or ") + std::string(to_string(f.model));
  text += named             ? std::string(to_string(*named))
          : fitting.empty() ? std::string("NO MODEL within 5 %")
                            : fitting + " (this slide cannot tell them apart)";
  for (const FrictionModelFit& f : fits)
    text += held ? printf_string("; %s %.7g m", to_string(f.model), f.distance_45)
                 : printf_string("; %s %.5g", to_string(f.model), f.ratio);
  return text;
}

Scene combine_scene(const Scene& scene) {
  const SlidePair pair = slide_pair(scene);
  if (pair.pulled)
    throw InputError(
        scene.name, 0, "world.gravity",
        "pulls its slide along the floor (an incline): a held slide's friction is the "
        "pull, not mu times its normal impulse, so the pair's coefficient is read from "
        "a slide launched along a level floor");
  Scene out = pair.along_axis;
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
  // A pull along x (an incline) adds its impulse to what the friction took.
  const Vec3 v0 = run.at(0, body).velocity, vn = run.at(n, body).velocity;
  const double t = static_cast<double>(run.recorded[n]) * h;
  return (v0.x() - vn.x() + scene.world.gravity.x() * t) / (vn.y() - v0.y() + t * g);
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
