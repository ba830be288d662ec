// Chipmunk 7.0.3's cpSpaceStep replayed in its own double arithmetic (cpFloat = double, Debian's
// build) and operation order, for one dynamic body on one static body, each with one box or one
// circle (a box or a ball on a floor): the discrete law a Chipmunk run must follow to the bit.
//
// The world is the one harness/core/chipmunk_world.hpp declares for the chipmunk adapter:
// cpSpaceNew, cpSpaceSetGravity, cpSpaceSetDamping, cpSpaceSetSleepTimeThreshold(INFINITY),
// cpSpaceSetIterations, cpSpaceSetCollisionSlop (collision bias and persistence at cpSpaceInit's
// defaults, whose values the world carries), then per body in the given order cpBodyNew(m, I) or
// cpBodyNewStatic, cpBodySetPosition, for a dynamic body cpBodySetVelocity, cpBodySetAngle and
// cpBodySetAngularVelocity, cpSpaceAddBody, and with contacts one shape added right after its
// body, cpCircleShapeNew(body, radius, cpvzero) for a radius > 0, else cpBoxShapeNew(body, 2 hx,
// 2 hy, 0), with cpShapeSetFriction and cpShapeSetElasticity. Each step replays cpSpaceStep in
// Chipmunk's order:
//   - cpBodyUpdatePosition: p += h (v + v_bias), a += h (w + w_bias), the transform rebuilt from
//     cos a and sin a; the pseudo-velocities cleared;
//   - the broad phase (cpBBTree with the static tree beside it): the dynamic shape's tree leaf
//     keeps a fat box (10 % of the shape's box each way, or 0.1 s of its velocity ahead) until
//     the shape's box leaves it; while that fat box overlaps the static shape's box the pair is
//     tested, as (dynamic, static) with no cached GJK start in the step the leaf is rebuilt, else
//     as (static, dynamic) from the GJK start cached in the pair, and collided when the two
//     shapes' own boxes overlap;
//   - cpCollide, the pair sorted circle before polygon (two of a kind in the order tested): for
//     two polygons GJK (EPA when the cores overlap) to the minimum separating axis, then the two
//     support edges clipped against each other for at most two points, each keyed by a hash of
//     its two features; for a circle and a polygon GJK from the circle's centre, one contact
//     (hash 0) when the distance is within the radius; for two circles one contact along the
//     centres; the arbiter's shape a, body a and normal (a to b) follow the sorted order;
//   - the arbiter: created on first contact, cpArbiterUpdate carrying the accumulated impulses of
//     points whose feature hash persists, elasticity e_a e_b and friction u_a u_b, marked cached
//     after a step without contact and dropped after collisionPersistence such steps (a cached
//     arbiter that touches again counts as a first contact: its carried impulses are not applied
//     as a warm start);
//   - cpArbiterPreStep (effective masses, the bias velocity from the penetration beyond the slop
//     at coefficient 1 - bias^h, the bounce target e (v_rel . n) of the velocities before this
//     step's gravity), cpBodyUpdateVelocity (v = v damping^h + g h), cpArbiterApplyCachedImpulse
//     (scaled by h/h_prev, 0 on the first step), then `iterations` passes of
//     cpArbiterApplyImpulse (bias impulse, normal impulse towards -bounce, friction clamped to
//     u jn).
// The algorithm follows Chipmunk 7.0.3 (MIT license, Scott Lembcke and Howling Moon Software); each
// ported function names its source file and function. A case it does not replay is refused rather
// than approximated: with contacts, not exactly two bodies, one dynamic and one static; without
// contacts (no shapes: free flight, any number of bodies) it replays every body.
#pragma once

#include <cstdint>
#include <vector>

#include "harness/core/chipmunk_world.hpp"

namespace dropcheck {

// One body as Chipmunk reports it: cpBodyGetPosition, cpBodyGetAngle, cpBodyGetVelocity,
// cpBodyGetAngularVelocity.
struct ChipmunkState {
  double x = 0, y = 0, angle = 0, vx = 0, vy = 0, w = 0;
};

// The states of every body after steps 0..steps of cpSpaceStep(space, h) on the space `world`
// declares: entry n*bodies + i is body i after step n (step 0: as created). Throws
// std::invalid_argument outside the scope: with contacts, not exactly two bodies, not one of them
// static; a static body with an angle, velocity or spin (the adapter sets none); a dynamic body
// without a positive, finite mass and moment; a negative radius; a box (radius 0) with a
// non-positive half extent (contacts only); negative friction or elasticity; an input not finite;
// h <= 0; iterations <= 0; damping < 0; steps < 0.
std::vector<ChipmunkState> chipmunk_replay(const ChipmunkWorld& world, double h,
                                           std::int64_t steps);

}  // namespace dropcheck
