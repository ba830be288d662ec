// Chipmunk 7.0.3's step for one dynamic and one static body, each with one box or one circle, in
// its own double order (harness/oracles/chipmunk_step.hpp). The algorithm follows Chipmunk 7.0.3
// (MIT license, Scott Lembcke and Howling Moon Software).
//
// Every expression keeps Chipmunk's operand order and grouping and its constants, so that the
// compiler rounds the same operations the same way; the file must be built without floating-point
// contraction (-ffp-contract=off), as Debian's x86-64 libchipmunk has none (plain SSE2, no FMA),
// and for the x86-64 baseline: with FMA in the instruction set (-march=native, -mfma), GCC 12 at
// -O3 turns the complex-multiplication pairs (vrotate, set_transform) into vfmaddsub despite
// -ffp-contract=off, a last-bit difference (-fno-tree-slp-vectorize avoids it).
// Chipmunk writes its constants as float literals; 0.0f, 0.5f, 1.0f and 2 are exact in double and
// are written here as doubles, 0.1f is not and stays a float literal. cos and sin (Chipmunk calls
// sincos), pow and sqrt are glibc's, as Chipmunk's. What cannot happen between two such shapes is
// left out and said so where it would have been: segments, circle offsets, rounded boxes,
// constraints, sleeping, sensors, collision handlers other than the default, shape filters,
// kinematic bodies.
#include "harness/oracles/chipmunk_step.hpp"

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace dropcheck {
namespace {
namespace chipmunk {  // apart from dropcheck's own Body, ...

// ---------------------------------------------------------------------------------------------
// chipmunk_types.h and chipmunk_private.h: scalars, hashes and the handful of constants.

using HashValue = std::uintptr_t;              // cpHashValue
using CollisionId = std::uint32_t;             // cpCollisionID
using Timestamp = unsigned int;                // cpTimestamp
constexpr double kFloatMin = DBL_MIN;          // CPFLOAT_MIN
constexpr HashValue kHashCoef = 3344921057ul;  // CP_HASH_COEF
constexpr int kMaxGjkIterations = 30;          // cpCollision.c, MAX_GJK_ITERATIONS
constexpr int kMaxEpaIterations = 30;          // cpCollision.c, MAX_EPA_ITERATIONS

// chipmunk_private.h, CP_HASH_PAIR: symmetric in its two arguments (64-bit wrap-around).
HashValue hash_pair(HashValue a, HashValue b) {
  return a * kHashCoef ^ b * kHashCoef;
}

// chipmunk_types.h, cpfmax, cpfmin, cpfclamp, cpfclamp01 (by comparison, NaN falls through)
double fmax_cp(double a, double b) {
  return (a > b) ? a : b;
}
double fmin_cp(double a, double b) {
  return (a < b) ? a : b;
}
double fclamp(double f, double min, double max) {
  return fmin_cp(fmax_cp(f, min), max);
}
double fclamp01(double f) {
  return fmax_cp(0.0, fmin_cp(f, 1.0));
}

// ---------------------------------------------------------------------------------------------
// cpVect.h: vectors.

struct Vect {
  double x = 0.0, y = 0.0;
};
constexpr Vect kZero{0.0, 0.0};  // cpvzero

// cpVect.h, cpvadd, cpvsub, cpvneg, cpvmult, cpvdot, cpvcross
Vect vadd(Vect a, Vect b) {
  return {a.x + b.x, a.y + b.y};
}
Vect vsub(Vect a, Vect b) {
  return {a.x - b.x, a.y - b.y};
}
Vect vneg(Vect v) {
  return {-v.x, -v.y};
}
Vect vmult(Vect v, double s) {
  return {v.x * s, v.y * s};
}
double vdot(Vect a, Vect b) {
  return a.x * b.x + a.y * b.y;
}
double vcross(Vect a, Vect b) {
  return a.x * b.y - a.y * b.x;
}

// cpVect.h, cpvperp (turned by +90 degrees) and cpvrperp (by -90 degrees)
Vect vperp(Vect v) {
  return {-v.y, v.x};
}
Vect vrperp(Vect v) {
  return {v.y, -v.x};
}

// cpVect.h, cpvrotate: complex multiplication, v1 turned by the angle of v2 (and scaled by |v2|).
Vect vrotate(Vect a, Vect b) {
  return {a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x};
}

// cpVect.h, cpvlengthsq, cpvlength, cpvlerp
double vlengthsq(Vect v) {
  return vdot(v, v);
}
double vlength(Vect v) {
  return std::sqrt(vdot(v, v));
}
Vect vlerp(Vect a, Vect b, double t) {
  return vadd(vmult(a, 1.0 - t), vmult(b, t));
}

// cpVect.h, cpvnormalize: v / (|v| + DBL_MIN), which is 0 for v = 0 instead of NaN.
Vect vnormalize(Vect v) {
  return vmult(v, 1.0 / (vlength(v) + kFloatMin));
}

// cpVect.h, cpvforangle: (cos a, sin a).
Vect vforangle(double a) {
  return {std::cos(a), std::sin(a)};
}

// ---------------------------------------------------------------------------------------------
// cpBB.h and cpTransform.h: bounding boxes and body frames.

struct BB {
  double l = 0.0, b = 0.0, r = 0.0, t = 0.0;
};

// cpBB.h, cpBBIntersects and cpBBContainsBB (closed boxes)
bool bb_intersects(const BB& a, const BB& b) {
  return (a.l <= b.r && b.l <= a.r && a.b <= b.t && b.b <= a.t);
}
bool bb_contains(const BB& bb, const BB& other) {
  return (bb.l <= other.l && bb.r >= other.r && bb.b <= other.b && bb.t >= other.t);
}

// cpBB.h, cpBBCenter: cpvlerp of the corners at 0.5.
Vect bb_center(const BB& bb) {
  return vlerp({bb.l, bb.b}, {bb.r, bb.t}, 0.5);
}

// chipmunk_types.h, cpTransform: x' = a x + c y + tx, y' = b x + d y + ty.
struct Transform {
  double a = 0.0, b = 0.0, c = 0.0, d = 0.0, tx = 0.0, ty = 0.0;
};

// cpTransform.h, cpTransformPoint and cpTransformVect
Vect transform_point(const Transform& t, Vect p) {
  return {t.a * p.x + t.c * p.y + t.tx, t.b * p.x + t.d * p.y + t.ty};
}
Vect transform_vect(const Transform& t, Vect v) {
  return {t.a * v.x + t.c * v.y, t.b * v.x + t.d * v.y};
}

// cpRobust.c, cpCheckPointGreater: c lies left of the segment a b (doubled coordinates).
bool check_point_greater(Vect a, Vect b, Vect c) {
  return (b.y - a.y) * (a.x + b.x - 2 * c.x) > (b.x - a.x) * (a.y + b.y - 2 * c.y);
}

// cpRobust.c, cpCheckAxis: p is no further along n than v0 or v1.
bool check_axis(Vect v0, Vect v1, Vect p, Vect n) {
  return vdot(p, n) <= fmax_cp(vdot(v0, n), vdot(v1, n));
}

// ---------------------------------------------------------------------------------------------
// cpBody.c: bodies, their frames and their integration.

struct Body {
  bool is_static = false;
  double m = 0.0, m_inv = 0.0, i = 0.0, i_inv = 0.0;
  Vect cog;  // the centre of gravity in the body frame: (0, 0), no shape carries mass
  Vect p, v, f;
  double a = 0.0, w = 0.0, t = 0.0;
  Vect v_bias;  // the pseudo-velocities of the position correction, spent by the next move
  double w_bias = 0.0;
  Transform transform;
};

// cpBody.c, SetTransform: the body frame for centre of gravity p and angle a.
void set_transform(Body& body, Vect p, double a) {
  const Vect rot = vforangle(a);
  const Vect c = body.cog;
  body.transform = {rot.x,
                    rot.y,
                    -rot.y,
                    rot.x,
                    p.x - (c.x * rot.x - c.y * rot.y),
                    p.y - (c.x * rot.y + c.y * rot.x)};
}

// cpBody.c, cpBodyInit with cpBodySetMass and cpBodySetMoment (0 gives an infinite inverse) and
// cpBodySetAngle(0).
Body body_new(double mass, double moment) {
  Body body;
  body.m = mass;
  body.m_inv = mass == 0.0 ? INFINITY : 1.0 / mass;
  body.i = moment;
  body.i_inv = moment == 0.0 ? INFINITY : 1.0 / moment;
  body.a = 0.0;
  set_transform(body, body.p, 0.0);
  return body;
}

// cpBody.c, cpBodyNewStatic: cpBodyNew(0, 0), then cpBodySetType(CP_BODY_TYPE_STATIC).
Body body_new_static() {
  Body body = body_new(0.0, 0.0);
  body.is_static = true;
  body.m = body.i = INFINITY;
  body.m_inv = body.i_inv = 0.0;
  body.v = kZero;
  body.w = 0.0;
  return body;
}

// cpBody.c, cpBodySetPosition: p is the centre of gravity, the given origin plus the turned cog.
void body_set_position(Body& body, Vect position) {
  body.p = vadd(transform_vect(body.transform, body.cog), position);
  set_transform(body, body.p, body.a);
}

// cpBody.c, cpBodySetAngle
void body_set_angle(Body& body, double angle) {
  body.a = angle;
  set_transform(body, body.p, angle);
}

// cpBody.c, cpBodyGetPosition: the frame's origin, rebuilt from the transform.
Vect body_get_position(const Body& body) {
  return transform_point(body.transform, kZero);
}

// cpBody.c, cpBodyUpdateVelocity: v = v d + (g + f/m) h, w = w d + t/I h (d = damping^h); the
// force and torque (zero here) are then cleared.
void update_velocity(Body& body, Vect gravity, double damping, double dt) {
  body.v = vadd(vmult(body.v, damping), vmult(vadd(gravity, vmult(body.f, body.m_inv)), dt));
  body.w = body.w * damping + body.t * body.i_inv * dt;
  body.f = kZero;
  body.t = 0.0;
}

// cpBody.c, cpBodyUpdatePosition: explicit move by the step-start velocity plus the bias velocity
// of the last solve, which is then cleared.
void update_position(Body& body, double dt) {
  body.p = vadd(body.p, vmult(vadd(body.v, body.v_bias), dt));
  body.a = body.a + (body.w + body.w_bias) * dt;
  set_transform(body, body.p, body.a);
  body.v_bias = kZero;
  body.w_bias = 0.0;
}

// ---------------------------------------------------------------------------------------------
// cpShape.c and cpPolyShape.c: a circle, or a box as a polygon of four splitting planes.

// chipmunk_structs.h, cpShapeType: the rank cpCollide sorts a pair by (no segments here).
enum class ShapeType { circle = 0, poly = 2 };

// chipmunk_structs.h, cpSplittingPlane: vertex i and the outward normal of the edge (i-1, i).
struct SplittingPlane {
  Vect v0, n;
};

// chipmunk_structs.h, cpShape with the fields of cpCircleShape and cpPolyShape after it: the type
// says which kind's fields are in use (the class pointer's role).
struct Shape {
  ShapeType type = ShapeType::poly;
  Body* body = nullptr;
  HashValue hashid = 0;     // the space's shape counter at cpSpaceAddShape
  BB bb;                    // after the last cache
  double e = 0.0, u = 0.0;  // elasticity, friction
  Vect surface_v;
  double r = 0.0;  // the circle's radius, or the polygon's rounding radius
  Vect c, tc;      // circle: its centre in the body frame, and in the world
  static constexpr int count = 4;
  SplittingPlane local[count];   // polygon: body frame
  SplittingPlane planes[count];  // polygon: world frame, after the last cache
};

// cpShape.c, cpCircleShapeNew and cpCircleShapeInit with cpShapeInit: centre `offset`, radius;
// no mass (the body's own mass and moment stay), elasticity and friction 0 until set.
Shape circle_shape_new(Body& body, double radius, Vect offset) {
  Shape circle;
  circle.type = ShapeType::circle;
  circle.c = offset;
  circle.r = radius;
  circle.body = &body;
  return circle;
}

// cpShape.c, cpCircleShapeCacheData with cpBB.h, cpBBNewForCircle: the centre in world
// coordinates and the square of side 2 r around it.
void circle_cache_data(Shape& circle) {
  const Vect c = circle.tc = transform_point(circle.body->transform, circle.c);
  const double r = circle.r;
  circle.bb = {c.x - r, c.y - r, c.x + r, c.y + r};
}

// cpPolyShape.c, SetVerts: the planes of a counter-clockwise vertex loop; normal i is the
// normalized right perpendicular of vertex i - vertex i-1.
void set_verts(Shape& poly, const Vect (&verts)[Shape::count]) {
  const int count = Shape::count;
  for (int i = 0; i < count; ++i) {
    const Vect a = verts[(i - 1 + count) % count];
    const Vect b = verts[i];
    poly.local[i] = {b, vnormalize(vrperp(vsub(b, a)))};
  }
}

// cpPolyShape.c, cpBoxShapeNew, cpBoxShapeInit, cpBoxShapeInit2 and cpPolyShapeInitRaw: corners
// (r, b), (r, t), (l, t), (l, b) of the box of half sizes width/2, height/2; no mass (the body's
// own mass and moment stay), elasticity and friction 0 until set.
Shape box_shape_new(Body& body, double width, double height, double radius) {
  const double hw = width / 2.0;
  const double hh = height / 2.0;
  const BB box{-hw, -hh, hw, hh};
  const Vect verts[Shape::count] = {{box.r, box.b}, {box.r, box.t}, {box.l, box.t}, {box.l, box.b}};
  Shape poly;
  poly.type = ShapeType::poly;
  poly.body = &body;
  set_verts(poly, verts);
  poly.r = radius;
  return poly;
}

// cpPolyShape.c, cpPolyShapeCacheData: the planes in world coordinates and their bounding box,
// widened by the radius.
void poly_cache_data(Shape& poly) {
  const Transform& transform = poly.body->transform;
  double l = INFINITY, r = -INFINITY;
  double b = INFINITY, t = -INFINITY;
  for (int i = 0; i < Shape::count; ++i) {
    const Vect v = transform_point(transform, poly.local[i].v0);
    const Vect n = transform_vect(transform, poly.local[i].n);
    poly.planes[i] = {v, n};
    l = fmin_cp(l, v.x);
    r = fmax_cp(r, v.x);
    b = fmin_cp(b, v.y);
    t = fmax_cp(t, v.y);
  }
  const double radius = poly.r;
  poly.bb = {l - radius, b - radius, r + radius, t + radius};
}

// cpShape.c, cpShapeUpdate / cpShapeCacheBB: the kind's cacheData at the body's frame.
void shape_cache_bb(Shape& shape) {
  if (shape.type == ShapeType::circle) {
    circle_cache_data(shape);
  } else {
    poly_cache_data(shape);
  }
}

// ---------------------------------------------------------------------------------------------
// cpCollision.c: support points, GJK, EPA, the contact points of two polygons, and the circles'
// single contacts.

// cpCollision.c, PolySupportPointIndex: the first vertex furthest along n.
int support_point_index(const Shape& poly, Vect n) {
  double max = -INFINITY;
  int index = 0;
  for (int i = 0; i < Shape::count; ++i) {
    const double d = vdot(poly.planes[i].v0, n);
    if (d > max) {
      max = d;
      index = i;
    }
  }
  return index;
}

// cpCollision.c, SupportPoint: a vertex and its index (the GJK cache's currency).
struct SupportPoint {
  Vect p;
  CollisionId index = 0;
};

// cpCollision.c, CircleSupportPoint: the centre, index 0, whatever n (GJK sees the circle as its
// centre; the radius is added to the distance and the contact afterwards).
SupportPoint circle_support_point(const Shape& circle, Vect) {
  return {circle.tc, 0};
}

// cpCollision.c, PolySupportPoint
SupportPoint poly_support_point(const Shape& poly, Vect n) {
  const int i = support_point_index(poly, n);
  return {poly.planes[i].v0, static_cast<CollisionId>(i)};
}

// cpCollision.c, MinkowskiPoint: b - a of two support points, id = index a << 8 | index b.
struct MinkowskiPoint {
  Vect a, b, ab;
  CollisionId id = 0;
};

// cpCollision.c, MinkowskiPointNew
MinkowskiPoint minkowski_point(SupportPoint a, SupportPoint b) {
  return {a.p, b.p, vsub(b.p, a.p), (a.index & 0xFF) << 8 | (b.index & 0xFF)};
}

// cpCollision.c, SupportPointFunc and SupportContext: the two shapes in cpCollide's order, each
// with its kind's support function.
using SupportPointFunc = SupportPoint (*)(const Shape&, Vect);
struct SupportContext {
  const Shape* shape1 = nullptr;
  const Shape* shape2 = nullptr;
  SupportPointFunc func1 = nullptr;
  SupportPointFunc func2 = nullptr;
};

// cpCollision.c, Support: the Minkowski difference's support point along n.
MinkowskiPoint support(const SupportContext& ctx, Vect n) {
  const SupportPoint a = ctx.func1(*ctx.shape1, vneg(n));
  const SupportPoint b = ctx.func2(*ctx.shape2, n);
  return minkowski_point(a, b);
}

// cpCollision.c, EdgePoint and Edge: a support edge, its end points keyed by
// CP_HASH_PAIR(shape hashid, vertex index), its radius and outward normal.
struct EdgePoint {
  Vect p;
  HashValue hash = 0;
};
struct Edge {
  EdgePoint a, b;
  double r = 0.0;
  Vect n;
};

// cpCollision.c, SupportEdgeForPoly: of the two edges at the vertex furthest along n, the one
// whose normal is closer to n.
Edge support_edge_for_poly(const Shape& poly, Vect n) {
  const int count = Shape::count;
  const int i1 = support_point_index(poly, n);
  const int i0 = (i1 - 1 + count) % count;
  const int i2 = (i1 + 1) % count;
  const SplittingPlane* planes = poly.planes;
  const HashValue hashid = poly.hashid;
  auto point = [&](int i) {
    return EdgePoint{planes[i].v0, hash_pair(hashid, static_cast<HashValue>(i))};
  };
  if (vdot(n, planes[i1].n) > vdot(n, planes[i2].n)) {
    return {point(i0), point(i1), poly.r, planes[i1].n};
  }
  return {point(i1), point(i2), poly.r, planes[i2].n};
}

// cpCollision.c, ClosestT: the parameter t in [-1, 1] of the point of segment a b closest to the
// origin, p(t) = a (1 - t)/2 + b (1 + t)/2.
double closest_t(Vect a, Vect b) {
  const Vect delta = vsub(b, a);
  return -fclamp(vdot(delta, vadd(a, b)) / vlengthsq(delta), -1.0, 1.0);
}

// cpCollision.c, LerpT: p(t) as above.
Vect lerp_t(Vect a, Vect b, double t) {
  const double ht = 0.5 * t;
  return vadd(vmult(a, 0.5 - ht), vmult(b, 0.5 + ht));
}

// cpCollision.c, ClosestDist: squared distance of segment v0 v1 from the origin.
double closest_dist(Vect v0, Vect v1) {
  return vlengthsq(lerp_t(v0, v1, closest_t(v0, v1)));
}

// cpCollision.c, ClosestPoints: the surface points (absolute), the separating axis n (from shape
// 1 to shape 2), the signed distance along it and the two Minkowski ids (the next GJK start).
struct ClosestPoints {
  Vect a, b, n;
  double d = 0.0;
  CollisionId id = 0;
};

// cpCollision.c, ClosestPointsNew: from the Minkowski edge closest to the origin; the axis is the
// edge's normal unless the closest point is an end of a separated edge (vertex against vertex),
// then the direction of that point.
ClosestPoints closest_points_new(const MinkowskiPoint& v0, const MinkowskiPoint& v1) {
  const double t = closest_t(v0.ab, v1.ab);
  const Vect p = lerp_t(v0.ab, v1.ab, t);
  const Vect pa = lerp_t(v0.a, v1.a, t);
  const Vect pb = lerp_t(v0.b, v1.b, t);
  const CollisionId id = (v0.id & 0xFFFF) << 16 | (v1.id & 0xFFFF);
  const Vect delta = vsub(v1.ab, v0.ab);
  const Vect n = vnormalize(vrperp(delta));
  const double d = vdot(n, p);
  if (d <= 0.0 || (-1.0 < t && t < 1.0)) return {pa, pb, n, d, id};
  const double d2 = vlength(p);
  const Vect n2 = vmult(p, 1.0 / (d2 + kFloatMin));
  return {pa, pb, n2, d2, id};
}

// cpCollision.c, EPA and EPARecurse (the recursion as a loop): grow the hull of the Minkowski
// difference towards the origin, each time beyond its edge closest to the origin, until the new
// support point repeats an end, lies on the edge, or 30 iterations are done.
ClosestPoints epa(const SupportContext& ctx, const MinkowskiPoint& v0, const MinkowskiPoint& v1,
                  const MinkowskiPoint& v2) {
  std::vector<MinkowskiPoint> hull{v0, v1, v2};
  for (int iteration = 1;; ++iteration) {
    const int count = static_cast<int>(hull.size());
    int mini = 0;
    double min_dist = INFINITY;
    for (int j = 0, i = count - 1; j < count; i = j, j++) {
      const double d = closest_dist(hull[i].ab, hull[j].ab);
      if (d < min_dist) {
        min_dist = d;
        mini = i;
      }
    }
    const MinkowskiPoint e0 = hull[mini];
    const MinkowskiPoint e1 = hull[(mini + 1) % count];
    const MinkowskiPoint p = support(ctx, vperp(vsub(e1.ab, e0.ab)));
    const bool duplicate = (p.id == e0.id || p.id == e1.id);
    if (duplicate || !check_point_greater(e0.ab, e1.ab, p.ab) || iteration >= kMaxEpaIterations) {
      return closest_points_new(e0, e1);
    }
    std::vector<MinkowskiPoint> hull2{p};  // p, then the old hull from e1 on, kept convex
    for (int i = 0; i < count; i++) {
      const int index = (mini + 1 + i) % count;
      const Vect h0 = hull2.back().ab;
      const Vect h1 = hull[index].ab;
      const Vect h2 = (i + 1 < count ? hull[(index + 1) % count] : p).ab;
      if (check_point_greater(h0, h2, h1)) hull2.push_back(hull[index]);
    }
    hull = std::move(hull2);
  }
}

// cpCollision.c, GJKRecurse (the recursion as a loop): keep the origin on the right of the
// Minkowski edge v0 v1; look beyond it; a triangle around the origin goes to EPA, no progress
// ends the search, else the support point replaces the end further from the origin.
ClosestPoints gjk_recurse(const SupportContext& ctx, MinkowskiPoint v0, MinkowskiPoint v1) {
  for (int iteration = 1;; ++iteration) {
    if (iteration > kMaxGjkIterations) return closest_points_new(v0, v1);
    if (check_point_greater(v1.ab, v0.ab, kZero)) std::swap(v0, v1);  // flip, same iteration
    const double t = closest_t(v0.ab, v1.ab);
    const Vect n =
        (-1.0 < t && t < 1.0 ? vperp(vsub(v1.ab, v0.ab)) : vneg(lerp_t(v0.ab, v1.ab, t)));
    const MinkowskiPoint p = support(ctx, n);
    if (check_point_greater(p.ab, v0.ab, kZero) && check_point_greater(v1.ab, p.ab, kZero)) {
      return epa(ctx, v0, p, v1);
    }
    if (check_axis(v0.ab, v1.ab, p.ab, n)) return closest_points_new(v0, v1);
    if (closest_dist(v0.ab, p.ab) < closest_dist(p.ab, v1.ab)) {
      v1 = p;
    } else {
      v0 = p;
    }
  }
}

// cpCollision.c, ShapePoint: a circle's centre (index 0); a polygon's vertex i, or 0 past the end.
SupportPoint shape_point(const Shape& shape, int i) {
  if (shape.type == ShapeType::circle) return {shape.tc, 0};
  const int index = (i < Shape::count ? i : 0);
  return {shape.planes[index].v0, static_cast<CollisionId>(index)};
}

// cpCollision.c, GJK: start from the cached vertex indices (id != 0), else from the support points
// across the line joining the two bounding boxes' centres; id takes the final edge's indices.
ClosestPoints gjk(const SupportContext& ctx, CollisionId& id) {
  MinkowskiPoint v0, v1;
  if (id) {
    v0 = minkowski_point(shape_point(*ctx.shape1, (id >> 24) & 0xFF),
                         shape_point(*ctx.shape2, (id >> 16) & 0xFF));
    v1 = minkowski_point(shape_point(*ctx.shape1, (id >> 8) & 0xFF),
                         shape_point(*ctx.shape2, (id)&0xFF));
  } else {
    const Vect axis = vperp(vsub(bb_center(ctx.shape1->bb), bb_center(ctx.shape2->bb)));
    v0 = support(ctx, axis);
    v1 = support(ctx, vneg(axis));
  }
  const ClosestPoints points = gjk_recurse(ctx, v0, v1);
  id = points.id;
  return points;
}

// chipmunk_structs.h, cpContact: offsets from the two bodies' centres (absolute until
// cpArbiterUpdate), effective masses, bounce and bias velocities, accumulated impulses and the
// feature hash that matches a point across steps.
struct Contact {
  Vect r1, r2;
  double n_mass = 0.0, t_mass = 0.0;
  double bounce = 0.0;
  double jn_acc = 0.0, jt_acc = 0.0, j_bias = 0.0;
  double bias = 0.0;
  HashValue hash = 0;
};

// chipmunk_structs.h, cpCollisionInfo
struct CollisionInfo {
  const Shape* a = nullptr;
  const Shape* b = nullptr;
  CollisionId id = 0;
  Vect n;
  int count = 0;
  Contact arr[2];  // CP_MAX_CONTACTS_PER_ARBITER
};

// cpCollision.c, cpCollisionInfoPushContact
void push_contact(CollisionInfo& info, Vect p1, Vect p2, HashValue hash) {
  Contact& con = info.arr[info.count];
  con.r1 = p1;
  con.r2 = p2;
  con.hash = hash;
  info.count++;
}

// cpCollision.c, ContactPoints: each end of one edge is projected onto the other edge (clamped to
// it, by the coordinate across n); a pair is a contact when its points overlap along n. The pairs
// are keyed (e1.a, e2.b) and (e1.b, e2.a).
void contact_points(const Edge& e1, const Edge& e2, const ClosestPoints& points,
                    CollisionInfo& info) {
  const double mindist = e1.r + e2.r;
  if (!(points.d <= mindist)) return;
  const Vect n = info.n = points.n;
  const double d_e1_a = vcross(e1.a.p, n);
  const double d_e1_b = vcross(e1.b.p, n);
  const double d_e2_a = vcross(e2.a.p, n);
  const double d_e2_b = vcross(e2.b.p, n);
  const double e1_denom = 1.0 / (d_e1_b - d_e1_a + kFloatMin);
  const double e2_denom = 1.0 / (d_e2_b - d_e2_a + kFloatMin);
  {
    const Vect p1 =
        vadd(vmult(n, e1.r), vlerp(e1.a.p, e1.b.p, fclamp01((d_e2_b - d_e1_a) * e1_denom)));
    const Vect p2 =
        vadd(vmult(n, -e2.r), vlerp(e2.a.p, e2.b.p, fclamp01((d_e1_a - d_e2_a) * e2_denom)));
    const double dist = vdot(vsub(p2, p1), n);
    if (dist <= 0.0) push_contact(info, p1, p2, hash_pair(e1.a.hash, e2.b.hash));
  }
  {
    const Vect p1 =
        vadd(vmult(n, e1.r), vlerp(e1.a.p, e1.b.p, fclamp01((d_e2_a - d_e1_a) * e1_denom)));
    const Vect p2 =
        vadd(vmult(n, -e2.r), vlerp(e2.a.p, e2.b.p, fclamp01((d_e1_b - d_e2_a) * e2_denom)));
    const double dist = vdot(vsub(p2, p1), n);
    if (dist <= 0.0) push_contact(info, p1, p2, hash_pair(e1.b.hash, e2.a.hash));
  }
}

// cpCollision.c, CircleToCircle: one contact, hash 0, when the centres are nearer than the radii's
// sum (strictly); n along the centres' difference, (1, 0) for coincident centres. The GJK id is
// not touched.
void circle_to_circle(const Shape& c1, const Shape& c2, CollisionInfo& info) {
  const double mindist = c1.r + c2.r;
  const Vect delta = vsub(c2.tc, c1.tc);
  const double distsq = vlengthsq(delta);
  if (distsq < mindist * mindist) {
    const double dist = std::sqrt(distsq);
    const Vect n = info.n = (dist != 0.0 ? vmult(delta, 1.0 / dist) : Vect{1.0, 0.0});
    push_contact(info, vadd(c1.tc, vmult(n, c1.r)), vadd(c2.tc, vmult(n, -c2.r)), 0);
  }
}

// cpCollision.c, CircleToPoly: GJK between the centre and the polygon; when the distance is within
// the radii's sum, one contact, hash 0: the circle's surface point along n and the polygon's
// closest point pushed by its rounding radius (along +n, as Chipmunk writes it; 0 here).
void circle_to_poly(const Shape& circle, const Shape& poly, CollisionInfo& info) {
  const SupportContext context{&circle, &poly, circle_support_point, poly_support_point};
  const ClosestPoints points = gjk(context, info.id);
  if (points.d <= circle.r + poly.r) {
    const Vect n = info.n = points.n;
    push_contact(info, vadd(points.a, vmult(n, circle.r)), vadd(points.b, vmult(n, poly.r)), 0);
  }
}

// cpCollision.c, PolyToPoly: GJK; when the rounded shapes touch, the contacts of the support edge
// of each along the axis (shape 1 along n, shape 2 against it).
void poly_to_poly(const Shape& poly1, const Shape& poly2, CollisionInfo& info) {
  const SupportContext context{&poly1, &poly2, poly_support_point, poly_support_point};
  const ClosestPoints points = gjk(context, info.id);
  if (points.d - poly1.r - poly2.r <= 0.0) {
    contact_points(support_edge_for_poly(poly1, points.n),
                   support_edge_for_poly(poly2, vneg(points.n)), points, info);
  }
}

// cpCollision.c, cpCollide: the pair sorted by shape type, circle before polygon (two of a kind
// keep the order they came in), then the collision function of the two types; info.a is the
// shape the normal points away from.
CollisionInfo collide(const Shape& a, const Shape& b, CollisionId id) {
  CollisionInfo info;
  info.a = &a;
  info.b = &b;
  info.id = id;
  info.n = kZero;
  if (a.type > b.type) std::swap(info.a, info.b);
  if (info.b->type == ShapeType::poly) {
    if (info.a->type == ShapeType::poly) {
      poly_to_poly(*info.a, *info.b, info);
    } else {
      circle_to_poly(*info.a, *info.b, info);
    }
  } else {
    circle_to_circle(*info.a, *info.b, info);
  }
  return info;
}

// ---------------------------------------------------------------------------------------------
// chipmunk_private.h: the impulse helpers of the contact solver.

// chipmunk_private.h, relative_velocity: velocity of the point on b minus that on a.
Vect relative_velocity(const Body& a, const Body& b, Vect r1, Vect r2) {
  const Vect v1_sum = vadd(a.v, vmult(vperp(r1), a.w));
  const Vect v2_sum = vadd(b.v, vmult(vperp(r2), b.w));
  return vsub(v2_sum, v1_sum);
}

// chipmunk_private.h, normal_relative_velocity
double normal_relative_velocity(const Body& a, const Body& b, Vect r1, Vect r2, Vect n) {
  return vdot(relative_velocity(a, b, r1, r2), n);
}

// chipmunk_private.h, apply_impulse and apply_impulses: -j on a at r1, +j on b at r2 (a static
// body has zero inverses, its velocity gains j*0).
void apply_impulse(Body& body, Vect j, Vect r) {
  body.v = vadd(body.v, vmult(j, body.m_inv));
  body.w += body.i_inv * vcross(r, j);
}
void apply_impulses(Body& a, Body& b, Vect r1, Vect r2, Vect j) {
  apply_impulse(a, vneg(j), r1);
  apply_impulse(b, j, r2);
}

// chipmunk_private.h, apply_bias_impulse and apply_bias_impulses: the same on v_bias, w_bias.
void apply_bias_impulse(Body& body, Vect j, Vect r) {
  body.v_bias = vadd(body.v_bias, vmult(j, body.m_inv));
  body.w_bias += body.i_inv * vcross(r, j);
}
void apply_bias_impulses(Body& a, Body& b, Vect r1, Vect r2, Vect j) {
  apply_bias_impulse(a, vneg(j), r1);
  apply_bias_impulse(b, j, r2);
}

// chipmunk_private.h, k_scalar_body and k_scalar: the mass a unit impulse along n at r1, r2 meets,
// 1/m_a + (r1 x n)^2/I_a + the same for b.
double k_scalar_body(const Body& body, Vect r, Vect n) {
  const double rcn = vcross(r, n);
  return body.m_inv + body.i_inv * rcn * rcn;
}
double k_scalar(const Body& a, const Body& b, Vect r1, Vect r2, Vect n) {
  return k_scalar_body(a, r1, n) + k_scalar_body(b, r2, n);
}

// ---------------------------------------------------------------------------------------------
// cpArbiter.c: the arbiter of the pair, its update and its share of the solver.

// cpArbiter.h, cpArbiterState (CP_ARBITER_STATE_IGNORE and _INVALIDATED need callbacks or shape
// removal).
enum class ArbiterState { first_collision, normal, cached };

// chipmunk_structs.h, cpArbiter: the pair's material, its contacts (the last collision's, kept
// while cached), the normal from a to b and the step it last touched.
struct Arbiter {
  double e = 0.0, u = 0.0;
  Vect surface_vr;
  const Shape* a = nullptr;
  const Shape* b = nullptr;
  Body* body_a = nullptr;
  Body* body_b = nullptr;
  Contact contacts[2];
  int count = 0;
  Vect n;
  Timestamp stamp = 0;
  ArbiterState state = ArbiterState::first_collision;
};

// cpArbiter.c, cpArbiterInit (from the space's pool in cpSpaceArbiterSetTrans)
Arbiter arbiter_init(const Shape& a, const Shape& b) {
  Arbiter arb;
  arb.a = &a;
  arb.body_a = a.body;
  arb.b = &b;
  arb.body_b = b.body;
  return arb;
}

// cpArbiter.c, cpArbiterUpdate: the new contacts relative to the bodies' centres, each taking the
// accumulated impulses of an old contact with its hash (the last such one); the shapes' product
// elasticity and friction, the tangential surface velocity (zero); a cached arbiter becomes a first
// collision again. The default handler is found and nothing is swapped.
void arbiter_update(Arbiter& arb, const CollisionInfo& info) {
  const Shape& a = *info.a;
  const Shape& b = *info.b;
  arb.a = &a;
  arb.body_a = a.body;
  arb.b = &b;
  arb.body_b = b.body;
  Contact contacts[2] = {info.arr[0], info.arr[1]};
  for (int i = 0; i < info.count; i++) {
    Contact& con = contacts[i];
    con.r1 = vsub(con.r1, a.body->p);
    con.r2 = vsub(con.r2, b.body->p);
    con.jn_acc = con.jt_acc = 0.0;
    for (int j = 0; j < arb.count; j++) {
      const Contact& old = arb.contacts[j];
      if (con.hash == old.hash) {
        con.jn_acc = old.jn_acc;
        con.jt_acc = old.jt_acc;
      }
    }
  }
  arb.contacts[0] = contacts[0];
  arb.contacts[1] = contacts[1];
  arb.count = info.count;
  arb.n = info.n;
  arb.e = a.e * b.e;
  arb.u = a.u * b.u;
  const Vect surface_vr = vsub(b.surface_v, a.surface_v);
  arb.surface_vr = vsub(surface_vr, vmult(info.n, vdot(surface_vr, info.n)));
  if (arb.state == ArbiterState::cached) arb.state = ArbiterState::first_collision;
}

// cpArbiter.c, cpArbiterPreStep: per contact the normal and tangent effective masses, the bias
// velocity -biasCoef min(0, dist + slop)/dt that pushes out the penetration beyond the slop, and
// the bounce target e (v_rel . n) of the velocities before gravity.
void arbiter_pre_step(Arbiter& arb, double dt, double slop, double bias) {
  const Body& a = *arb.body_a;
  const Body& b = *arb.body_b;
  const Vect n = arb.n;
  const Vect body_delta = vsub(b.p, a.p);
  for (int i = 0; i < arb.count; i++) {
    Contact& con = arb.contacts[i];
    con.n_mass = 1.0 / k_scalar(a, b, con.r1, con.r2, n);
    con.t_mass = 1.0 / k_scalar(a, b, con.r1, con.r2, vperp(n));
    const double dist = vdot(vadd(vsub(con.r2, con.r1), body_delta), n);
    con.bias = -bias * fmin_cp(0.0, dist + slop) / dt;
    con.j_bias = 0.0;
    con.bounce = normal_relative_velocity(a, b, con.r1, con.r2, n) * arb.e;
  }
}

// cpArbiter.c, cpArbiterApplyCachedImpulse: the warm start, the carried impulses (jn along n, jt
// along perp n) times h/h_prev; none on a first collision.
void arbiter_apply_cached_impulse(Arbiter& arb, double dt_coef) {
  if (arb.state == ArbiterState::first_collision) return;
  Body& a = *arb.body_a;
  Body& b = *arb.body_b;
  const Vect n = arb.n;
  for (int i = 0; i < arb.count; i++) {
    const Contact& con = arb.contacts[i];
    const Vect j = vrotate(n, {con.jn_acc, con.jt_acc});
    apply_impulses(a, b, con.r1, con.r2, vmult(j, dt_coef));
  }
}

// cpArbiter.c, cpArbiterApplyImpulse: per contact, from the velocities as they stand: the bias
// impulse towards the bias velocity (accumulated >= 0, on v_bias/w_bias), the normal impulse
// towards -bounce (accumulated >= 0), the friction impulse that stops the slip (accumulated within
// +-u jn); the bias increment is applied first, then normal and friction together.
void arbiter_apply_impulse(Arbiter& arb) {
  Body& a = *arb.body_a;
  Body& b = *arb.body_b;
  const Vect n = arb.n;
  const Vect surface_vr = arb.surface_vr;
  const double friction = arb.u;
  for (int i = 0; i < arb.count; i++) {
    Contact& con = arb.contacts[i];
    const double n_mass = con.n_mass;
    const Vect r1 = con.r1;
    const Vect r2 = con.r2;
    const Vect vb1 = vadd(a.v_bias, vmult(vperp(r1), a.w_bias));
    const Vect vb2 = vadd(b.v_bias, vmult(vperp(r2), b.w_bias));
    const Vect vr = vadd(relative_velocity(a, b, r1, r2), surface_vr);
    const double vbn = vdot(vsub(vb2, vb1), n);
    const double vrn = vdot(vr, n);
    const double vrt = vdot(vr, vperp(n));

    const double jbn = (con.bias - vbn) * n_mass;
    const double jbn_old = con.j_bias;
    con.j_bias = fmax_cp(jbn_old + jbn, 0.0);

    const double jn = -(con.bounce + vrn) * n_mass;
    const double jn_old = con.jn_acc;
    con.jn_acc = fmax_cp(jn_old + jn, 0.0);

    const double jt_max = friction * con.jn_acc;
    const double jt = -vrt * con.t_mass;
    const double jt_old = con.jt_acc;
    con.jt_acc = fclamp(jt_old + jt, -jt_max, jt_max);

    apply_bias_impulses(a, b, r1, r2, vmult(n, con.j_bias - jbn_old));
    apply_impulses(a, b, r1, r2, vrotate(n, {con.jn_acc - jn_old, con.jt_acc - jt_old}));
  }
}

// ---------------------------------------------------------------------------------------------
// cpSpace.c, cpBBTree.c and cpSpaceStep.c: the space, its broad phase and its step.

struct Space {
  Space() = default;
  Space(const Space&) = delete;  // bodies, shapes and the arbiter point into it
  Space& operator=(const Space&) = delete;

  int iterations = 10;
  Vect gravity;
  double damping = 1.0;
  double collision_slop = 0.1;
  double collision_bias = 0.0;
  Timestamp collision_persistence = 3;
  Timestamp stamp = 0;
  double curr_dt = 0.0;
  std::vector<Body> bodies;  // the world's order; never resized after creation
  std::vector<Body*> dynamic_bodies;
  // With contacts: the dynamic and the static shape and the broad phase's record of them.
  std::optional<Shape> dynamic_shape, static_shape;
  BB leaf_bb;               // the dynamic tree leaf's fat box
  bool pair = false;        // the leaves' pair exists (cpBBTree's Pair)
  CollisionId pair_id = 0;  // its cached GJK start
  // The pair's arbiter: in the space's cachedArbiters set, and in this step's arbiter list.
  std::optional<Arbiter> arbiter;
  bool arbiter_cached = false;
  bool arbiter_listed = false;
};

// cpBBTree.c, GetBB with cpSpace.c, ShapeVelocityFunc: the dynamic tree's fat box, the shape's
// box grown by 10 % of its size each way or, where farther, by 0.1 s of the body's velocity.
BB fat_bb(const Shape& shape) {
  const BB bb = shape.bb;
  const double coef = 0.1f;
  const double x = (bb.r - bb.l) * coef;
  const double y = (bb.t - bb.b) * coef;
  const Vect v = vmult(shape.body->v, 0.1f);
  return {bb.l + fmin_cp(-x, v.x), bb.b + fmin_cp(-y, v.y), bb.r + fmax_cp(x, v.x),
          bb.t + fmax_cp(y, v.y)};
}

// cpSpace.c, cpSpaceAddShape with cpBBTree.c, cpBBTreeInsert, LeafAddPairs and MarkLeafQuery: each
// shape cached at its body's frame, and for the second of the two shapes the leaves' pair made if
// the dynamic leaf's fat box overlaps the static shape's box (either creation order gives the pair
// (static, dynamic) with no cached GJK start).
void add_shapes(Space& s, Shape& dynamic_shape, Shape& static_shape) {
  shape_cache_bb(dynamic_shape);
  shape_cache_bb(static_shape);
  s.leaf_bb = fat_bb(dynamic_shape);
  s.pair = bb_intersects(s.leaf_bb, static_shape.bb);
  s.pair_id = 0;
}

// cpSpaceStep.c, cpSpaceArbiterSetTrans / cpHashSet.c, cpHashSetInsert: the pair's cached
// arbiter (in either shape order), or a new one.
Arbiter& cached_arbiter(Space& s, const Shape& a, const Shape& b) {
  if (!s.arbiter_cached) {
    s.arbiter = arbiter_init(a, b);
    s.arbiter_cached = true;
  }
  return *s.arbiter;
}

// cpSpaceStep.c, cpSpaceCollideShapes: rejected unless the shapes' boxes overlap (same body,
// filters and constraints cannot reject here); collided; with contacts the arbiter is updated, its
// begin and preSolve (the default handler's) accept, no sensor or two infinite masses: it joins
// the step's list and is stamped. Returns the GJK start for the pair's cache.
CollisionId collide_shapes(Space& s, const Shape& a, const Shape& b, CollisionId id) {
  if (!bb_intersects(a.bb, b.bb)) return id;
  const CollisionInfo info = collide(a, b, id);
  if (info.count == 0) return info.id;
  Arbiter& arb = cached_arbiter(s, *info.a, *info.b);
  arbiter_update(arb, info);
  s.arbiter_listed = true;
  arb.stamp = s.stamp;
  return info.id;
}

// cpBBTree.c, cpBBTreeReindexQuery with LeafUpdate, MarkSubtree, MarkLeaf and MarkLeafQuery, for
// one dynamic leaf beside one static leaf: a leaf whose fat box no longer holds the shape's box is
// rebuilt around it (its pair cleared) and queried against the static tree, which collides
// (dynamic, static) with no GJK start and remakes the pair (its id 0); a leaf left in place walks
// its pairs, colliding (static, dynamic) with the pair's cached id and keeping the one returned.
void reindex_query(Space& s) {
  Shape& dynamic_shape = *s.dynamic_shape;
  Shape& static_shape = *s.static_shape;
  if (!bb_contains(s.leaf_bb, dynamic_shape.bb)) {
    s.leaf_bb = fat_bb(dynamic_shape);
    s.pair = bb_intersects(s.leaf_bb, static_shape.bb);
    s.pair_id = 0;
    if (s.pair) collide_shapes(s, dynamic_shape, static_shape, 0);
  } else if (s.pair) {
    s.pair_id = collide_shapes(s, static_shape, dynamic_shape, s.pair_id);
  }
}

// cpSpaceStep.c, cpSpaceArbiterSetFilter: an arbiter that did not touch this step turns cached;
// after collisionPersistence steps without touching it goes back to the pool, its contacts gone
// (even from this step's list, if it is on it).
void filter_arbiters(Space& s) {
  if (!s.arbiter_cached) return;
  Arbiter& arb = *s.arbiter;
  const Timestamp ticks = s.stamp - arb.stamp;
  // Never both bodies static or sleeping: one is dynamic and sleeping is off.
  if (ticks >= 1 && arb.state != ArbiterState::cached) arb.state = ArbiterState::cached;
  if (ticks >= s.collision_persistence) {
    arb.count = 0;
    s.arbiter_cached = false;
  }
}

// cpSpaceStep.c, cpSpaceStep: move the bodies, find the contacts, drop stale arbiters, prestep,
// integrate the velocities, warm start, then the impulse iterations. The listed arbiter's state
// returns to normal at the next step's start (after its first step a first collision is a normal
// one). No constraints, callbacks or sleeping components.
void space_step(Space& s, double dt) {
  s.stamp++;
  const double prev_dt = s.curr_dt;
  s.curr_dt = dt;
  if (s.arbiter_listed) s.arbiter->state = ArbiterState::normal;
  s.arbiter_listed = false;

  for (Body* body : s.dynamic_bodies) update_position(*body, dt);
  if (s.dynamic_shape) {
    shape_cache_bb(*s.dynamic_shape);  // cpShapeUpdateFunc over the dynamic tree
    reindex_query(s);
  }
  filter_arbiters(s);

  Arbiter* arb = s.arbiter_listed ? &*s.arbiter : nullptr;
  const double slop = s.collision_slop;
  const double bias_coef = 1.0 - std::pow(s.collision_bias, dt);
  if (arb) arbiter_pre_step(*arb, dt, slop, bias_coef);

  const double damping = std::pow(s.damping, dt);
  for (Body* body : s.dynamic_bodies) update_velocity(*body, s.gravity, damping, dt);

  const double dt_coef = (prev_dt == 0.0 ? 0.0 : dt / prev_dt);
  if (arb) arbiter_apply_cached_impulse(*arb, dt_coef);
  for (int i = 0; i < s.iterations; i++) {
    if (arb) arbiter_apply_impulse(*arb);
  }
}

// ---------------------------------------------------------------------------------------------
// The replay's own frame: checks, creation, read-out.

void check_scope(const ChipmunkWorld& world, double h, std::int64_t steps) {
  auto fail = [](const char* why) {
    throw std::invalid_argument(std::string("chipmunk_replay: ") + why);
  };
  auto finite = [](double v) { return std::isfinite(v); };
  if (world.contacts) {
    if (world.bodies.size() != 2) fail("with contacts it needs exactly two bodies");
    if (world.bodies[0].is_static == world.bodies[1].is_static) {
      fail("with contacts it needs one dynamic and one static body");
    }
  }
  for (const ChipmunkBox& b : world.bodies) {
    for (double v : {b.hx, b.hy, b.radius, b.x, b.y, b.angle, b.vx, b.vy, b.w, b.mass, b.moment,
                     b.friction, b.elasticity}) {
      if (!finite(v)) fail("a body parameter is not finite");
    }
    if (b.radius < 0.0) fail("a negative radius");
    if (world.contacts && b.radius == 0.0 && !(b.hx > 0.0 && b.hy > 0.0)) {
      fail("a box's half extent is not positive");
    }
    if (b.friction < 0.0 || b.elasticity < 0.0) fail("negative friction or elasticity");
    if (b.is_static && (b.angle != 0.0 || b.vx != 0.0 || b.vy != 0.0 || b.w != 0.0)) {
      fail("a static body with an angle, velocity or spin (the adapter sets none)");
    }
    if (!b.is_static && !(b.mass > 0.0 && b.moment > 0.0)) {
      fail("a dynamic body needs a positive mass and moment");
    }
  }
  for (double v : {world.gx, world.gy, world.damping, world.collision_slop, world.collision_bias}) {
    if (!finite(v)) fail("a space parameter is not finite");
  }
  if (world.damping < 0.0) fail("negative damping");
  if (world.iterations <= 0) fail("iterations must be positive");
  if (!finite(h) || !(h > 0.0)) fail("h must be positive and finite");
  if (steps < 0) fail("negative step count");
}

// cpBody.c, cpBodyNew / cpBodyNewStatic and the adapter's setters, in its order.
Body create_body(const ChipmunkBox& box) {
  Body body = box.is_static ? body_new_static() : body_new(box.mass, box.moment);
  body_set_position(body, {box.x, box.y});
  if (!box.is_static) {
    body.v = {box.vx, box.vy};
    body_set_angle(body, box.angle);
    body.w = box.w;
  }
  return body;
}

// cpCircleShapeNew(body, radius, cpvzero) for a radius, else cpBoxShapeNew(body, 2 hx, 2 hy, 0),
// with cpShapeSetFriction and cpShapeSetElasticity; hashid counts the shapes in the order they
// are added.
Shape create_shape(Body& body, const ChipmunkBox& box, HashValue hashid) {
  Shape shape = box.radius > 0.0 ? circle_shape_new(body, box.radius, kZero)
                                 : box_shape_new(body, 2 * box.hx, 2 * box.hy, 0.0);
  shape.hashid = hashid;
  shape.u = box.friction;
  shape.e = box.elasticity;
  return shape;
}

// cpSpace.c, cpSpaceInit and the setters the adapter calls, then the bodies and shapes. Filled in
// place: bodies, shapes and the arbiter point at each other.
void create_space(const ChipmunkWorld& world, Space& s) {
  s.gravity = {world.gx, world.gy};
  s.damping = world.damping;
  s.iterations = world.iterations;
  s.collision_slop = world.collision_slop;
  s.collision_bias = world.collision_bias;
  s.collision_persistence = world.collision_persistence;
  s.bodies.reserve(world.bodies.size());
  for (const ChipmunkBox& box : world.bodies) s.bodies.push_back(create_body(box));
  for (Body& body : s.bodies) {
    if (!body.is_static) s.dynamic_bodies.push_back(&body);
  }
  if (world.contacts) {
    const std::size_t d = world.bodies[0].is_static ? 1 : 0;
    s.dynamic_shape = create_shape(s.bodies[d], world.bodies[d], d);
    s.static_shape = create_shape(s.bodies[1 - d], world.bodies[1 - d], 1 - d);
    add_shapes(s, *s.dynamic_shape, *s.static_shape);
  }
}

ChipmunkState state_of(const Body& b) {
  const Vect p = body_get_position(b);
  return {p.x, p.y, b.a, b.v.x, b.v.y, b.w};
}

}  // namespace chipmunk
}  // namespace

std::vector<ChipmunkState> chipmunk_replay(const ChipmunkWorld& world, double h,
                                           std::int64_t steps) {
  chipmunk::check_scope(world, h, steps);
  chipmunk::Space s;
  chipmunk::create_space(world, s);
  std::vector<ChipmunkState> out;
  out.reserve(static_cast<std::size_t>(steps + 1) * s.bodies.size());
  for (std::int64_t n = 0;; ++n) {
    for (const chipmunk::Body& b : s.bodies) out.push_back(chipmunk::state_of(b));
    if (n == steps) break;
    chipmunk::space_step(s, h);
  }
  return out;
}

}  // namespace dropcheck
