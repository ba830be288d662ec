// Box2D 2.4.1's b2World::Step replayed in its own float arithmetic and operation order, for one
// dynamic and one static body, each a box or a circle: the discrete law a Box2D run must follow to
// the bit.
//
// The world is the one the box2d adapter (adapters/box2d.cpp) builds from harness/core/
// box2d_world.hpp's Box2dBox list: b2World(gravity), SetAllowSleeping(false),
// SetAutoClearForces(true), then per body in the given order CreateBody (allowSleep = false, awake)
// and CreateFixture with one shape of the body's density, friction and restitution (restitution
// threshold the fixture default, 1 m/s): a b2PolygonShape::SetAsBox(hx, hy) (Box2D's 0.01 m polygon
// skin), or, when radius > 0, a b2CircleShape of that m_radius at the body's origin (m_p = 0).
// Warm starting and continuous physics stay on (Box2D's defaults), sub-stepping off; no forces but
// gravity. Each step replays, in Box2D's order:
//   - the contact pairing of the broad-phase: a contact between the two fixtures exists from the
//     FindNewContacts after their fat AABBs (0.1 m margin, 4x the last displacement ahead) overlap
//     until the Collide that finds them apart; its fixture A is body 0's (the lower proxy id),
//     except that a polygon and a circle always make the polygon fixture A (b2Contact::Create);
//   - b2ContactManager::Collide: b2CollidePolygons, b2CollidePolygonAndCircle or b2CollideCircles,
//     and the manifold id matching that carries the last step's impulses to the points that
//     persist;
//   - b2World::Solve: gravity, Pade damping, the sequential-impulse contact solver (warm start
//     scaled by dt/dt0, restitution as a velocity bias, friction then the normal solve: one point
//     alone, two as a block), the translation and rotation clamps, the position iterations with
//     their early exit;
//   - b2World::SolveTOI: the time of impact along both sweeps (conservative advancement over GJK),
//     the advance to it and a sub-step of the rest of the step (20 TOI position iterations, no warm
//     start), at most b2_maxSubSteps + 1 times a step.
// The algorithm follows Box2D 2.4.1 (MIT license, Erin Catto); each ported function names its
// source file and function. A case it does not replay (not exactly one dynamic and one static body)
// is refused rather than approximated.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "harness/core/box2d_world.hpp"

namespace dropcheck {

// b2World::Step's iteration counts.
struct Box2dSolver {
  int velocity_iterations = 8;
  int position_iterations = 3;
};

// One body as Box2D reports it: GetPosition(), GetAngle(), GetLinearVelocity(),
// GetAngularVelocity().
struct Box2dState {
  float x = 0.0f, y = 0.0f, angle = 0.0f;
  float vx = 0.0f, vy = 0.0f, w = 0.0f;
};

// The states of every body after steps 0..steps of b2World::Step(h, velocity_iterations,
// position_iterations) under gravity (gx, gy): entry n*bodies.size() + i is body i after step n
// (step 0: as created, after the fixture's mass set-up). Throws std::invalid_argument outside the
// scope: not exactly two bodies, not one of them static, the dynamic one without positive density,
// a negative radius, a box (radius 0) with a non-positive half extent, h or an input not finite,
// h <= 0, negative iterations or steps. A circle's hx and hy are not used.
std::vector<Box2dState> box2d_replay(std::span<const Box2dBox> bodies, float gx, float gy, float h,
                                     const Box2dSolver& solver, std::int64_t steps);

}  // namespace dropcheck
