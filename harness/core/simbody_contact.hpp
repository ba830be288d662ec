// What the simbody adapter (adapters/simbody.cpp) builds for contact, as Simbody 3.7's own
// parameters: declared once, for the adapter and for the force law that predicts it
// (hunt_crossley_states, harness/oracles/replayed_contact.cpp).
//
// Simbody 3.7's HuntCrossleyForce (its header's documentation, simbody/internal/
// HuntCrossleyForce.h; a later source computes the pair's stiffness otherwise, and Debian's runs
// follow this one) pushes a sphere out of a half-space with, at depth d and penetration rate r
// (both from the state at the step start),
//   s1 = E2^(2/3)/(E1^(2/3) + E2^(2/3)), E = (s1*E1^(2/3))^(3/2), c = c1*s1 + c2*(1 - s1)
//                                             (every surface here gets the same E: E/2^(3/2))
//   f = (4/3)*sqrt(R)*E*d^(3/2)*(1 + 1.5*c*r) (R the sphere's radius: a half-space is flat),
//   applied when f > 0 (it never pulls)
// and friction f*(min(s/vt, 1)*(ud + 2*(us - ud)/(1 + (s/vt)^2)) + uv*s) against a slip s.
// SemiExplicitEulerIntegrator steps it as any force: v += h*a(x, v); x += h*v.
//
// The adapter's choices:
//   stiffness    each surface's E such that a sphere resting on a floor under gravity g
//                oscillates with a period of kPeriodSteps steps (its linearised stiffness
//                1.5*K^(2/3)*(m*g)^(1/3) = m*(2*pi/(kPeriodSteps*h))^2, K = (4/3)*sqrt(R)*E_pair):
//                stiff enough to hold it, soft enough for the step to resolve an impact
//   dissipation  from the scene's restitution e: the c whose continuous contact (this force, under
//                gravity) returns e times the sphere's first impact speed, sqrt(v_y^2 + 2*g*gap)
//                and at least the speed of a fall from its own radius, found by bisection (Hunt and
//                Crossley's e = 1 - c*v holds for a small c*v only); e = 0 gives the largest c
//                the bisection reaches, e = 1 none
//   friction     the scene's mu as static and dynamic friction, no viscous part, transition
//                velocity 0.01 m/s (Simbody's default)
//   floor        a static box's top face as a half-space (its extent ignored)
// Scope: dynamic spheres (the lightest sets the stiffness, the first the impact speed).
#pragma once

#include "harness/core/scene.hpp"

namespace dropcheck {

inline constexpr double kPeriodSteps = 20.0;

struct SimbodyContact {
  double stiffness = 0.0;             // E of every surface (Simbody's "stiffness"), N/m^2
  double dissipation = 0.0;           // c of every surface, s/m
  double friction = 0.0;              // mu, static and dynamic
  double transition_velocity = 0.01;  // m/s
};

// The contact `scene` gets at step h.
SimbodyContact simbody_contact(const Scene& scene, double h);

// The pair's stiffness of two surfaces of stiffness E, as HuntCrossleyForce combines them:
// (s1*E^(2/3))^(3/2) with s1 = 1/2, that is E/2^(3/2).
double pair_stiffness(double E);

// HuntCrossleyForce's normal force on a sphere of radius `radius` at `depth` (> 0) into a
// half-space, penetrating at `rate` m/s (negative: leaving), before its clamp at 0.
double hunt_crossley_force(const SimbodyContact& c, double radius, double depth, double rate);

}  // namespace dropcheck
