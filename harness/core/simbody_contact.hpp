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
//
// A box is a ContactGeometry::Brick under Simbody's CompliantContactSubsystem, whose
// BrickHalfSpacePenalty (Simbody/src/CompliantContactSubsystem.cpp, calcPointHalfSpacePenaltyForce)
// takes the brick's face most nearly facing the half-space and pushes at each of its vertices that
// is x > 0 deep, with both surfaces' stiffness k and dissipation c (sH = k/(k + k) = 1/2):
//   f = (k/2)*x*(1 + c*r)   (r = dx/dt), none when f <= 0, at the point x/2 above the vertex,
//   friction f*mu(s) against the slip s of that point, mu(s) = us*step5(s/vt) below vt, us up to
//   3*vt, ud beyond (stribeck below; us = ud here, no viscous part).
// The adapter's choices:
//   stiffness    k such that a brick resting flat (four vertices) oscillates with a period of
//                kPeriodSteps steps: 4*(k/2) = m*(2*pi/(kPeriodSteps*h))^2 = m*omega^2
//   dissipation  without a restitution, the rest oscillation critically damped (its damping
//                4*(k/2)*x_rest*c = m*g*c is 2*m*omega, c = 2*omega/g), but at most 1/v for the
//                first impact speed v: in the first contact step, x ~ v*h deep, the rate term adds
//                c*v times the spring, and at c*v = 52 (a 10 m fall, h = 1/60) one step of it
//                throws the box out at several times v; with a restitution e, the c whose
//                continuous flat landing returns e of the first impact speed (bisection)
//   friction     the scene's mu as static and dynamic, no viscous part; transition velocity
//                vt = 3*kStribeckSlope*mu*|g|*h. The steepest slope of mu(s) is 1.875*mu/vt; a
//                twist about the normal meets 3 times the friction per unit inertia that a slide
//                does (each vertex pushes at r^2 = a^2 + c^2 from the centre of a box of half
//                sides a and c, whose moment is m*(a^2 + c^2)/3). So one explicit step takes at
//                most the whole deviation of a twist off its steady value and never overshoots
//                it. Simbody's default, 0.01 m/s, makes its friction chatter at these steps, and
//                at a third of this vt a creeping box starts to twist and roll, growing 1e13-fold
//                in 300 steps: unstable modes no replay follows from its rounding
// Scope: dynamic boxes (the lightest sets the stiffness, the first the impact speed), never
// touching one another (Simbody 3.7 tracks a brick against a half-space only).
#pragma once

#include "harness/core/scene.hpp"

namespace dropcheck {

inline constexpr double kPeriodSteps = 20.0;

struct SimbodyContact {
  bool bricks = false;                // the scene's boxes (a brick's penalty), not its spheres
  double stiffness = 0.0;             // E of every surface (Simbody's "stiffness"), N/m^2; of a
                                      // brick, k in N/m
  double dissipation = 0.0;           // c of every surface, s/m
  double friction = 0.0;              // mu, static and dynamic
  double transition_velocity = 0.01;  // m/s
};

// The contact `scene` gets at step h: of its spheres, or of its boxes when it has no sphere.
SimbodyContact simbody_contact(const Scene& scene, double h);

// The largest slope of step5, 30*x^2*(1 - x)^2 at x = 1/2.
inline constexpr double kStribeckSlope = 1.875;

// Simbody's dry friction coefficient at a slip of `slip` transition velocities (stribeck in
// CompliantContactSubsystem.cpp, no viscous part): us*step5(slip) below 1, easing from us to ud
// up to 3, ud beyond; step5(x) = x^3*(10 + x*(6*x - 15)).
double stribeck(double us, double ud, double slip);

// The pair's stiffness of two surfaces of stiffness E, as HuntCrossleyForce combines them:
// (s1*E^(2/3))^(3/2) with s1 = 1/2, that is E/2^(3/2).
double pair_stiffness(double E);

// HuntCrossleyForce's normal force on a sphere of radius `radius` at `depth` (> 0) into a
// half-space, penetrating at `rate` m/s (negative: leaving), before its clamp at 0.
double hunt_crossley_force(const SimbodyContact& c, double radius, double depth, double rate);

// BrickHalfSpacePenalty's normal force at one vertex `depth` (> 0) into a half-space, penetrating
// at `rate` m/s, before its clamp at 0: (k/2)*depth*(1 + c*rate).
double brick_vertex_force(const SimbodyContact& c, double depth, double rate);

}  // namespace dropcheck
