#include "harness/oracles/stack.hpp"

#include <algorithm>
#include <cmath>

#include "harness/oracles/contact_laws.hpp"
#include "harness/oracles/landing.hpp"

namespace dropcheck {
namespace {

// `upper`'s centre lies strictly inside `lower`'s top face (x-z): a centre on an edge balances
// between two columns, and neither carries its load alone.
bool over_body(const Body& upper, const Body& lower) {
  return std::abs(upper.position.x() - lower.position.x()) < lower.half_extents.x() &&
         std::abs(upper.position.z() - lower.position.z()) < lower.half_extents.z();
}

// The x-z footprints of a and b overlap (open rectangles: boxes that only touch at an edge do not).
bool overlaps(const Body& a, const Body& b) {
  return std::abs(a.position.x() - b.position.x()) < a.half_extents.x() + b.half_extents.x() &&
         std::abs(a.position.z() - b.position.z()) < a.half_extents.z() + b.half_extents.z();
}

// Every body that shares a member's footprint above the floor is a member: no load the column does
// not count rests on it, and nothing else stands in its way.
bool closed(const Scene& scene, const StackSetup& s) {
  const double floor_top = top_of(scene.bodies[s.floor]);
  for (std::size_t j = 0; j < scene.bodies.size(); ++j) {
    if (j == s.floor || top_of(scene.bodies[j]) <= floor_top) continue;
    const bool member = std::any_of(s.levels.begin(), s.levels.end(),
                                    [&](const StackLevel& l) { return l.body == j; });
    if (member) continue;
    for (const StackLevel& l : s.levels)
      if (overlaps(scene.bodies[j], scene.bodies[l.body])) return false;
  }
  return true;
}

// A body a stack may hold: a dynamic box at rest, pushed by nothing.
bool stackable(const Scene& scene, std::size_t i) {
  const Body& b = scene.bodies[i];
  return !b.is_static && b.shape == Shape::box && b.velocity == Vec3::Zero() && !pushed(scene, i);
}

}  // namespace

std::vector<StackSetup> stack_setups(const Scene& scene) {
  std::vector<StackSetup> out;
  const Vec3& g = scene.world.gravity;
  if (!floor_contact(scene) || !level_gravity(scene)) return out;
  // A column starts with a body resting on its floor (the landing oracle's floor); the next level
  // is the lowest stackable body over the level under it, with its bottom at or above that top.
  for (const LandingSetup& l : landing_setups(scene)) {
    const Body& first = scene.bodies[l.body];
    if (!stackable(scene, l.body) || std::abs(first.position.y() - l.rest_height) > 1e-9) continue;
    StackSetup s{l.body,
                 l.floor,
                 l.floor_top,
                 -g.y(),
                 scene.world.damping_rate,
                 {{l.body, 1, l.rest_height, first.mass, 0.0, 0.0}}};
    for (;;) {
      const StackLevel& under_level = s.levels.back();
      const Body& under = scene.bodies[under_level.body];
      long next = -1;
      for (std::size_t j = 0; j < scene.bodies.size(); ++j) {
        const Body& b = scene.bodies[j];
        if (!stackable(scene, j) || !over_body(b, under) || bottom_of(b) < top_of(under)) continue;
        if (next < 0 || b.position.y() < scene.bodies[static_cast<std::size_t>(next)].position.y())
          next = static_cast<long>(j);
      }
      if (next < 0) break;
      const Body& b = scene.bodies[static_cast<std::size_t>(next)];
      s.levels.push_back({static_cast<std::size_t>(next), under_level.level + 1,
                          under_level.rest_height + under.half_extents.y() + b.half_extents.y(),
                          b.mass, 0.0, under.mass});
    }
    if (s.levels.size() < 2 || !closed(scene, s)) continue;
    double load = 0.0;  // top down: each body and everything above it
    for (auto it = s.levels.rbegin(); it != s.levels.rend(); ++it) it->load = load += it->mass;
    out.push_back(std::move(s));
  }
  return out;
}

StackPrediction predict_stack(const StackSetup& setup, std::size_t level, const EngineInfo& info,
                              double h) {
  StackPrediction p;
  for (std::size_t k = 0; k <= level && k < setup.levels.size(); ++k) {
    const StackLevel& l = setup.levels[k];
    p.sink += contact_sink(info.stack_law, setup.g * l.load, l.mass, l.mass_below, h);
    p.offset += info.rest_offset;
    if (l.mass_below <= 0.0) continue;  // on the static floor: nothing to sweep against
    const double r = sweep_residual(info.stack_law, l.load, l.mass_below);
    if (r > p.residual) {
      p.residual = r;
      p.load = l.load;
      p.mass = l.mass_below;
    }
  }
  return p;
}

}  // namespace dropcheck
