// Box2D 2.4.1's step for one dynamic and one static body, each a box or a circle, in its own float
// order (harness/oracles/box2d_step.hpp). The algorithm follows Box2D 2.4.1 (MIT license, Erin
// Catto).
//
// Every expression keeps Box2D's operand order and grouping, its float types and its constants
// (built from the same float literals), so that the compiler rounds the same operations the same
// way; the file must be built without floating-point contraction (-ffp-contract=off), as Box2D's
// own x86-64 build has none. What cannot happen between two such bodies is left out and said so
// where it would have been: edges and chains, joints, sensors, bullets, sleeping, listeners.
#include "harness/oracles/box2d_step.hpp"

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

namespace dropcheck {
namespace {
namespace box2d {  // apart from dropcheck's own World, Body, ...

// ---------------------------------------------------------------------------------------------
// b2_common.h: the constants, as Box2D's macros build them (lengths in meters, 1 unit per meter).

constexpr float kMaxFloat = FLT_MAX;
constexpr float kEpsilon = FLT_EPSILON;
constexpr float kPi = 3.14159265359f;
constexpr float kLinearSlop = 0.005f * 1.0f;
constexpr float kPolygonRadius = 2.0f * kLinearSlop;  // the polygon skin
constexpr float kAabbExtension = 0.1f * 1.0f;         // fat AABB margin
constexpr float kAabbMultiplier = 4.0f;               // fat AABB look-ahead over a displacement
constexpr int kMaxSubSteps = 8;                       // TOI events per contact and step, + 1
constexpr int kMaxPolygonVertices = 8;
constexpr float kMaxLinearCorrection = 0.2f * 1.0f;
constexpr float kMaxTranslation = 2.0f * 1.0f;
constexpr float kMaxTranslationSquared = kMaxTranslation * kMaxTranslation;
constexpr float kMaxRotation = 0.5f * kPi;
constexpr float kMaxRotationSquared = kMaxRotation * kMaxRotation;
constexpr float kBaumgarte = 0.2f;
constexpr float kToiBaumgarte = 0.75f;
constexpr float kRestitutionThreshold = 1.0f * 1.0f;  // b2FixtureDef::restitutionThreshold

// ---------------------------------------------------------------------------------------------
// b2_math.h: vectors, rotations, transforms and sweeps.

// b2_math.h, b2Vec2
struct Vec2 {
  float x = 0.0f, y = 0.0f;
};

// b2_math.h, b2Vec2's operators and the free operator+, operator-, operator*(float, b2Vec2)
Vec2 operator+(Vec2 a, Vec2 b) {
  return {a.x + b.x, a.y + b.y};
}
Vec2 operator-(Vec2 a, Vec2 b) {
  return {a.x - b.x, a.y - b.y};
}
Vec2 operator-(Vec2 a) {
  return {-a.x, -a.y};
}
Vec2 operator*(float s, Vec2 a) {
  return {s * a.x, s * a.y};
}
void operator+=(Vec2& a, Vec2 b) {
  a.x += b.x, a.y += b.y;
}
void operator-=(Vec2& a, Vec2 b) {
  a.x -= b.x, a.y -= b.y;
}
void operator*=(Vec2& a, float s) {
  a.x *= s, a.y *= s;
}

// b2_math.h, b2Dot and the three b2Cross
float dot(Vec2 a, Vec2 b) {
  return a.x * b.x + a.y * b.y;
}
float cross(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}
Vec2 cross(Vec2 a, float s) {
  return {s * a.y, -s * a.x};
}  // a turned by -90 degrees, times s
Vec2 cross(float s, Vec2 a) {
  return {-s * a.y, s * a.x};
}  // a turned by +90 degrees, times s

// b2_math.h, b2Min, b2Max, b2Abs, b2Clamp (by comparison, as Box2D's templates)
Vec2 vmin(Vec2 a, Vec2 b) {
  return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y};
}
Vec2 vmax(Vec2 a, Vec2 b) {
  return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y};
}
float min_f(float a, float b) {
  return a < b ? a : b;
}
float max_f(float a, float b) {
  return a > b ? a : b;
}
float abs_f(float a) {
  return a > 0.0f ? a : -a;
}
float clamp(float a, float low, float high) {
  return max_f(low, min_f(a, high));
}

// b2_math.h, b2Vec2::Length (sqrtf), b2Distance and b2DistanceSquared
float length(Vec2 a) {
  return std::sqrt(a.x * a.x + a.y * a.y);
}
float distance(Vec2 a, Vec2 b) {
  return length(a - b);
}
float distance_squared(Vec2 a, Vec2 b) {
  const Vec2 c = a - b;
  return dot(c, c);
}

// b2_math.h, b2Vec2::Normalize: unit length, unless shorter than epsilon (then left as is, 0).
float normalize(Vec2& a) {
  const float len = length(a);
  if (len < kEpsilon) return 0.0f;
  const float inv = 1.0f / len;
  a.x *= inv;
  a.y *= inv;
  return len;
}

// b2_math.h, b2Mat22 (column vectors ex, ey).
struct Mat22 {
  Vec2 ex, ey;
};

// b2_math.h, b2Mul(b2Mat22, b2Vec2)
Vec2 mul(const Mat22& m, Vec2 v) {
  return {m.ex.x * v.x + m.ey.x * v.y, m.ex.y * v.x + m.ey.y * v.y};
}

// b2_math.h, b2Mat22::GetInverse: the adjugate over the determinant (zero matrix if singular).
Mat22 inverse(const Mat22& m) {
  const float a = m.ex.x, b = m.ey.x, c = m.ex.y, d = m.ey.y;
  float det = a * d - b * c;
  if (det != 0.0f) det = 1.0f / det;
  Mat22 out;
  out.ex.x = det * d;
  out.ey.x = -det * b;
  out.ex.y = -det * c;
  out.ey.y = det * a;
  return out;
}

// b2_math.h, b2Rot: sine and cosine of the angle.
struct Rot {
  float s = 0.0f, c = 1.0f;
};

// b2_math.h, b2Rot::Set (sinf, cosf)
Rot rot(float angle) {
  return {std::sin(angle), std::cos(angle)};
}

// b2_math.h, b2Mul(b2Rot, b2Vec2) and b2MulT(b2Rot, b2Vec2): rotate by q, by q^T
Vec2 mul(Rot q, Vec2 v) {
  return {q.c * v.x - q.s * v.y, q.s * v.x + q.c * v.y};
}
Vec2 mul_t(Rot q, Vec2 v) {
  return {q.c * v.x + q.s * v.y, -q.s * v.x + q.c * v.y};
}

// b2_math.h, b2MulT(b2Rot, b2Rot): q^T r
Rot mul_t(Rot q, Rot r) {
  return {q.c * r.s - q.s * r.c, q.c * r.c + q.s * r.s};
}

// b2_math.h, b2Transform: a body frame (origin p, rotation q).
struct Xf {
  Vec2 p;
  Rot q;
};

// b2_math.h, b2Mul(b2Transform, b2Vec2): a local point in world coordinates.
Vec2 mul(const Xf& t, Vec2 v) {
  const float x = (t.q.c * v.x - t.q.s * v.y) + t.p.x;
  const float y = (t.q.s * v.x + t.q.c * v.y) + t.p.y;
  return {x, y};
}

// b2_math.h, b2MulT(b2Transform, b2Vec2): a world point in local coordinates.
Vec2 mul_t(const Xf& t, Vec2 v) {
  const float px = v.x - t.p.x;
  const float py = v.y - t.p.y;
  const float x = (t.q.c * px + t.q.s * py);
  const float y = (-t.q.s * px + t.q.c * py);
  return {x, y};
}

// b2_math.h, b2MulT(b2Transform, b2Transform): frame b seen from frame a.
Xf mul_t(const Xf& a, const Xf& b) {
  Xf c;
  c.q = mul_t(a.q, b.q);
  c.p = mul_t(a.q, b.p - a.p);
  return c;
}

// b2_math.h, b2Sweep: the motion of a body's centre of mass over the step, from (c0, a0) at
// alpha0 to (c, a) at 1, with the centre at localCenter in the body frame.
struct Sweep {
  Vec2 local_center, c0, c;
  float a0 = 0.0f, a = 0.0f;
  float alpha0 = 0.0f;

  // b2_math.h, b2Sweep::GetTransform: the body frame at fraction beta, linearly interpolated.
  Xf transform(float beta) const {
    Xf xf;
    xf.p = (1.0f - beta) * c0 + beta * c;
    const float angle = (1.0f - beta) * a0 + beta * a;
    xf.q = rot(angle);
    xf.p -= mul(xf.q, local_center);
    return xf;
  }

  // b2_math.h, b2Sweep::Advance: move the start to time alpha (c and a stay).
  void advance(float alpha) {
    const float beta = (alpha - alpha0) / (1.0f - alpha0);
    c0 += beta * (c - c0);
    a0 += beta * (a - a0);
    alpha0 = alpha;
  }

  // b2_math.h, b2Sweep::Normalize: the start angle into [0, 2 pi), both angles shifted alike.
  void normalize() {
    const float two_pi = 2.0f * kPi;
    const float d = two_pi * std::floor(a0 / two_pi);
    a0 -= d;
    a -= d;
  }
};

// ---------------------------------------------------------------------------------------------
// b2_polygon_shape.cpp, b2_circle_shape.cpp and b2_collision.h: the shapes, their mass and their
// bounding boxes.

struct Polygon {
  Vec2 vertices[4];
  Vec2 normals[4];
  int count = 4;
  float radius = kPolygonRadius;  // b2PolygonShape's constructor
};

// b2_polygon_shape.cpp, b2PolygonShape::SetAsBox(hx, hy): corners counter-clockwise from
// (-hx, -hy), edge i from vertex i to i+1 with outward normal i.
Polygon set_as_box(float hx, float hy) {
  Polygon p;
  p.vertices[0] = {-hx, -hy};
  p.vertices[1] = {hx, -hy};
  p.vertices[2] = {hx, hy};
  p.vertices[3] = {-hx, hy};
  p.normals[0] = {0.0f, -1.0f};
  p.normals[1] = {1.0f, 0.0f};
  p.normals[2] = {0.0f, 1.0f};
  p.normals[3] = {-1.0f, 0.0f};
  return p;
}

struct MassData {
  float mass = 0.0f;
  Vec2 center;
  float I = 0.0f;  // about the body origin
};

// b2_polygon_shape.cpp, b2PolygonShape::ComputeMass: a fan of triangles from vertex 0 (s), each
// with area D/2 (D = cross of its edges e1, e2), centroid s + (e1 + e2)/3 and second moment about
// s of D/12 * (e1x^2 + e1x e2x + e2x^2 + same in y); the moment is moved to the centroid, then
// to the origin.
MassData compute_mass(const Polygon& p, float density) {
  Vec2 center{0.0f, 0.0f};
  float area = 0.0f;
  float I = 0.0f;
  const Vec2 s = p.vertices[0];
  const float k_inv3 = 1.0f / 3.0f;
  for (int i = 0; i < p.count; ++i) {
    const Vec2 e1 = p.vertices[i] - s;
    const Vec2 e2 = i + 1 < p.count ? p.vertices[i + 1] - s : p.vertices[0] - s;
    const float D = cross(e1, e2);
    const float triangle_area = 0.5f * D;
    area += triangle_area;
    center += triangle_area * k_inv3 * (e1 + e2);
    const float ex1 = e1.x, ey1 = e1.y;
    const float ex2 = e2.x, ey2 = e2.y;
    const float intx2 = ex1 * ex1 + ex2 * ex1 + ex2 * ex2;
    const float inty2 = ey1 * ey1 + ey2 * ey1 + ey2 * ey2;
    I += (0.25f * k_inv3 * D) * (intx2 + inty2);
  }
  MassData m;
  m.mass = density * area;
  center *= 1.0f / area;
  m.center = center + s;
  m.I = density * I;
  m.I += m.mass * (dot(m.center, m.center) - dot(center, center));
  return m;
}

// b2_circle_shape.h, b2CircleShape: the centre m_p in the body frame (the body's origin here) and
// b2Shape::m_radius, for a circle its whole radius rather than a skin.
struct Circle {
  Vec2 p;
  float radius = 0.0f;
};

// b2_circle_shape.cpp, b2CircleShape::ComputeMass: a disc, I = m (r^2/2 + |p|^2) about the origin.
MassData compute_mass(const Circle& c, float density) {
  MassData m;
  m.mass = density * kPi * c.radius * c.radius;
  m.center = c.p;
  m.I = m.mass * (0.5f * c.radius * c.radius + dot(c.p, c.p));
  return m;
}

// b2_shape.h, b2Shape: the fixture's shape, a box or a circle by m_type (e_polygon, e_circle).
struct Shape {
  bool is_circle = false;
  Polygon polygon;
  Circle circle;

  // b2Shape::m_radius: the polygon skin or the circle's radius.
  float radius() const { return is_circle ? circle.radius : polygon.radius; }
};

// b2_shape.h, b2Shape::ComputeMass (virtual)
MassData compute_mass(const Shape& s, float density) {
  return s.is_circle ? compute_mass(s.circle, density) : compute_mass(s.polygon, density);
}

// b2_collision.h, b2AABB
struct Aabb {
  Vec2 lower, upper;
};

// b2_polygon_shape.cpp, b2PolygonShape::ComputeAABB: the corners' bounds plus the skin.
Aabb compute_aabb(const Polygon& p, const Xf& xf) {
  Vec2 lower = mul(xf, p.vertices[0]);
  Vec2 upper = lower;
  for (int i = 1; i < p.count; ++i) {
    const Vec2 v = mul(xf, p.vertices[i]);
    lower = vmin(lower, v);
    upper = vmax(upper, v);
  }
  const Vec2 r{p.radius, p.radius};
  return {lower - r, upper + r};
}

// b2_circle_shape.cpp, b2CircleShape::ComputeAABB: the centre's square of half side r.
Aabb compute_aabb(const Circle& c, const Xf& xf) {
  const Vec2 p = xf.p + mul(xf.q, c.p);
  return {{p.x - c.radius, p.y - c.radius}, {p.x + c.radius, p.y + c.radius}};
}

// b2_shape.h, b2Shape::ComputeAABB (virtual)
Aabb compute_aabb(const Shape& s, const Xf& xf) {
  return s.is_circle ? compute_aabb(s.circle, xf) : compute_aabb(s.polygon, xf);
}

// b2_collision.h, b2AABB::Combine, GetCenter, Contains and b2TestOverlap.
Aabb combine(const Aabb& a, const Aabb& b) {
  return {vmin(a.lower, b.lower), vmax(a.upper, b.upper)};
}
Vec2 center(const Aabb& a) {
  return 0.5f * (a.lower + a.upper);
}
bool contains(const Aabb& outer, const Aabb& inner) {
  bool result = true;
  result = result && outer.lower.x <= inner.lower.x;
  result = result && outer.lower.y <= inner.lower.y;
  result = result && inner.upper.x <= outer.upper.x;
  result = result && inner.upper.y <= outer.upper.y;
  return result;
}
bool test_overlap(const Aabb& a, const Aabb& b) {
  const Vec2 d1 = b.lower - a.upper;
  const Vec2 d2 = a.lower - b.upper;
  if (d1.x > 0.0f || d1.y > 0.0f) return false;
  if (d2.x > 0.0f || d2.y > 0.0f) return false;
  return true;
}

// ---------------------------------------------------------------------------------------------
// b2_collision.h/.cpp, b2_collide_polygon.cpp and b2_collide_circle.cpp: the contact manifold.

// b2_collision.h, b2ContactFeature / b2ContactID: which features (vertex 0, face 1) of A and B
// make a point; equal ids (b2ContactID::key) mark the same point across steps.
struct ContactId {
  std::uint8_t index_a = 0, index_b = 0, type_a = 0, type_b = 0;
};
constexpr std::uint8_t kVertex = 0, kFace = 1;
bool same_key(const ContactId& a, const ContactId& b) {
  return a.index_a == b.index_a && a.index_b == b.index_b && a.type_a == b.type_a &&
         a.type_b == b.type_b;
}

struct ManifoldPoint {
  Vec2 local_point;
  float normal_impulse = 0.0f, tangent_impulse = 0.0f;
  ContactId id;
};

// b2_collision.h, b2Manifold: circles: A's centre in A's frame, B's centre (the one point) in B's,
// no normal; face_a: the normal and plane point in A's frame, the points in B's; face_b the other
// way round.
enum class ManifoldType { circles, face_a, face_b };
struct Manifold {
  ManifoldPoint points[2];
  Vec2 local_normal, local_point;
  ManifoldType type = ManifoldType::face_a;
  int point_count = 0;
};

struct ClipVertex {
  Vec2 v;
  ContactId id;
};

// b2_collide_polygon.cpp, b2FindMaxSeparation: over poly1's faces, the largest of the least
// distances of poly2's vertices in front of the face (in poly2's frame).
float find_max_separation(int& edge_index, const Polygon& poly1, const Xf& xf1,
                          const Polygon& poly2, const Xf& xf2) {
  const Xf xf = mul_t(xf2, xf1);
  int best_index = 0;
  float max_separation = -kMaxFloat;
  for (int i = 0; i < poly1.count; ++i) {
    const Vec2 n = mul(xf.q, poly1.normals[i]);
    const Vec2 v1 = mul(xf, poly1.vertices[i]);
    float si = kMaxFloat;
    for (int j = 0; j < poly2.count; ++j) {
      const float sij = dot(n, poly2.vertices[j] - v1);
      if (sij < si) si = sij;
    }
    if (si > max_separation) {
      max_separation = si;
      best_index = i;
    }
  }
  edge_index = best_index;
  return max_separation;
}

// b2_collide_polygon.cpp, b2FindIncidentEdge: poly2's face most anti-parallel to the reference
// face edge1 of poly1, as its two world vertices.
void find_incident_edge(ClipVertex c[2], const Polygon& poly1, const Xf& xf1, int edge1,
                        const Polygon& poly2, const Xf& xf2) {
  const Vec2 normal1 = mul_t(xf2.q, mul(xf1.q, poly1.normals[edge1]));
  int index = 0;
  float min_dot = kMaxFloat;
  for (int i = 0; i < poly2.count; ++i) {
    const float d = dot(normal1, poly2.normals[i]);
    if (d < min_dot) {
      min_dot = d;
      index = i;
    }
  }
  const int i1 = index;
  const int i2 = i1 + 1 < poly2.count ? i1 + 1 : 0;
  const auto e1 = static_cast<std::uint8_t>(edge1);
  c[0].v = mul(xf2, poly2.vertices[i1]);
  c[0].id = {e1, static_cast<std::uint8_t>(i1), kFace, kVertex};
  c[1].v = mul(xf2, poly2.vertices[i2]);
  c[1].id = {e1, static_cast<std::uint8_t>(i2), kFace, kVertex};
}

// b2_collision.cpp, b2ClipSegmentToLine: the part of segment vIn behind the line
// dot(normal, p) = offset; a cut end becomes (vertex of A, face of B).
int clip_segment_to_line(ClipVertex v_out[2], const ClipVertex v_in[2], Vec2 normal, float offset,
                         int vertex_index_a) {
  int count = 0;
  const float distance0 = dot(normal, v_in[0].v) - offset;
  const float distance1 = dot(normal, v_in[1].v) - offset;
  if (distance0 <= 0.0f) v_out[count++] = v_in[0];
  if (distance1 <= 0.0f) v_out[count++] = v_in[1];
  if (distance0 * distance1 < 0.0f) {
    const float interp = distance0 / (distance0 - distance1);
    v_out[count].v = v_in[0].v + interp * (v_in[1].v - v_in[0].v);
    v_out[count].id = {static_cast<std::uint8_t>(vertex_index_a), v_in[0].id.index_b, kVertex,
                       kFace};
    ++count;
  }
  return count;
}

// b2_collide_polygon.cpp, b2CollidePolygons: reference face = the face of largest separation, B's
// only when it beats A's by 0.1*slop; the incident edge is clipped to the reference face's side
// planes (widened by the skins) and its points within the skins of the face are kept.
void collide_polygons(Manifold& manifold, const Polygon& poly_a, const Xf& xf_a,
                      const Polygon& poly_b, const Xf& xf_b) {
  manifold.point_count = 0;
  const float total_radius = poly_a.radius + poly_b.radius;
  int edge_a = 0;
  const float separation_a = find_max_separation(edge_a, poly_a, xf_a, poly_b, xf_b);
  if (separation_a > total_radius) return;
  int edge_b = 0;
  const float separation_b = find_max_separation(edge_b, poly_b, xf_b, poly_a, xf_a);
  if (separation_b > total_radius) return;

  const float k_tol = 0.1f * kLinearSlop;
  const bool flip = separation_b > separation_a + k_tol;
  const Polygon& poly1 = flip ? poly_b : poly_a;  // reference
  const Polygon& poly2 = flip ? poly_a : poly_b;  // incident
  const Xf xf1 = flip ? xf_b : xf_a;
  const Xf xf2 = flip ? xf_a : xf_b;
  const int edge1 = flip ? edge_b : edge_a;
  manifold.type = flip ? ManifoldType::face_b : ManifoldType::face_a;

  ClipVertex incident[2];
  find_incident_edge(incident, poly1, xf1, edge1, poly2, xf2);

  const int iv1 = edge1;
  const int iv2 = edge1 + 1 < poly1.count ? edge1 + 1 : 0;
  Vec2 v11 = poly1.vertices[iv1];
  Vec2 v12 = poly1.vertices[iv2];
  Vec2 local_tangent = v12 - v11;
  normalize(local_tangent);
  const Vec2 local_normal = cross(local_tangent, 1.0f);
  const Vec2 plane_point = 0.5f * (v11 + v12);
  const Vec2 tangent = mul(xf1.q, local_tangent);
  const Vec2 normal = cross(tangent, 1.0f);
  v11 = mul(xf1, v11);
  v12 = mul(xf1, v12);
  const float front_offset = dot(normal, v11);
  const float side_offset1 = -dot(tangent, v11) + total_radius;
  const float side_offset2 = dot(tangent, v12) + total_radius;

  ClipVertex clip1[2], clip2[2];
  if (clip_segment_to_line(clip1, incident, -tangent, side_offset1, iv1) < 2) return;
  if (clip_segment_to_line(clip2, clip1, tangent, side_offset2, iv2) < 2) return;

  manifold.local_normal = local_normal;
  manifold.local_point = plane_point;
  int point_count = 0;
  for (int i = 0; i < 2; ++i) {
    const float separation = dot(normal, clip2[i].v) - front_offset;
    if (separation <= total_radius) {
      ManifoldPoint& cp = manifold.points[point_count];
      cp.local_point = mul_t(xf2, clip2[i].v);
      cp.id = clip2[i].id;
      if (flip) {  // the features as seen from A
        const ContactId cf = cp.id;
        cp.id = {cf.index_b, cf.index_a, cf.type_b, cf.type_a};
      }
      ++point_count;
    }
  }
  manifold.point_count = point_count;
}

// b2_collide_circle.cpp, b2CollideCircles: one point (id 0) when the centres are within rA + rB;
// the normal is left to the world manifold (centre A to centre B).
void collide_circles(Manifold& manifold, const Circle& circle_a, const Xf& xf_a,
                     const Circle& circle_b, const Xf& xf_b) {
  manifold.point_count = 0;
  const Vec2 p_a = mul(xf_a, circle_a.p);
  const Vec2 p_b = mul(xf_b, circle_b.p);
  const Vec2 d = p_b - p_a;
  const float dist_sqr = dot(d, d);
  const float radius = circle_a.radius + circle_b.radius;
  if (dist_sqr > radius * radius) return;
  manifold.type = ManifoldType::circles;
  manifold.local_point = circle_a.p;
  manifold.local_normal = {0.0f, 0.0f};
  manifold.point_count = 1;
  manifold.points[0].local_point = circle_b.p;
  manifold.points[0].id = {};
}

// b2_collide_circle.cpp, b2CollidePolygonAndCircle: in A's frame, the face of largest separation
// of the circle's centre (none beyond rA + rB); a centre behind every face takes that face's
// normal; else the centre's projection on the face picks a region: past an end vertex the normal
// runs from that vertex to the centre (within rA + rB), between them it is the face's normal.
// Always one point (id 0, e_faceA), the circle's centre.
void collide_polygon_and_circle(Manifold& manifold, const Polygon& polygon_a, const Xf& xf_a,
                                const Circle& circle_b, const Xf& xf_b) {
  manifold.point_count = 0;
  const Vec2 c = mul(xf_b, circle_b.p);
  const Vec2 c_local = mul_t(xf_a, c);
  int normal_index = 0;
  float separation = -kMaxFloat;
  const float radius = polygon_a.radius + circle_b.radius;
  const int vertex_count = polygon_a.count;
  const Vec2* vertices = polygon_a.vertices;
  const Vec2* normals = polygon_a.normals;
  for (int i = 0; i < vertex_count; ++i) {
    const float s = dot(normals[i], c_local - vertices[i]);
    if (s > radius) return;
    if (s > separation) {
      separation = s;
      normal_index = i;
    }
  }
  const int vert_index1 = normal_index;
  const int vert_index2 = vert_index1 + 1 < vertex_count ? vert_index1 + 1 : 0;
  const Vec2 v1 = vertices[vert_index1];
  const Vec2 v2 = vertices[vert_index2];
  Vec2 local_normal, local_point;
  if (separation < kEpsilon) {  // the centre inside the polygon
    local_normal = normals[normal_index];
    local_point = 0.5f * (v1 + v2);
  } else {
    const float u1 = dot(c_local - v1, v2 - v1);
    const float u2 = dot(c_local - v2, v1 - v2);
    if (u1 <= 0.0f) {  // beyond v1
      if (distance_squared(c_local, v1) > radius * radius) return;
      local_normal = c_local - v1;
      normalize(local_normal);
      local_point = v1;
    } else if (u2 <= 0.0f) {  // beyond v2
      if (distance_squared(c_local, v2) > radius * radius) return;
      local_normal = c_local - v2;
      normalize(local_normal);
      local_point = v2;
    } else {  // over the face
      const Vec2 face_center = 0.5f * (v1 + v2);
      const float s = dot(c_local - face_center, normals[vert_index1]);
      if (s > radius) return;
      local_normal = normals[vert_index1];
      local_point = face_center;
    }
  }
  manifold.point_count = 1;
  manifold.type = ManifoldType::face_a;
  manifold.local_normal = local_normal;
  manifold.local_point = local_point;
  manifold.points[0].local_point = circle_b.p;
  manifold.points[0].id = {};
}

// b2_collision.h, b2WorldManifold: the world normal (A to B) and each point midway between the
// two skins' surfaces.
struct WorldManifold {
  Vec2 normal;
  Vec2 points[2];
};

// b2_collision.cpp, b2WorldManifold::Initialize; for circles the normal joins the centres ((1, 0)
// if they coincide within epsilon) and the point lies midway between the two surfaces on it.
WorldManifold world_manifold(const Manifold& m, const Xf& xf_a, float radius_a, const Xf& xf_b,
                             float radius_b) {
  WorldManifold wm;
  if (m.point_count == 0) return wm;
  if (m.type == ManifoldType::circles) {
    wm.normal = {1.0f, 0.0f};
    const Vec2 point_a = mul(xf_a, m.local_point);
    const Vec2 point_b = mul(xf_b, m.points[0].local_point);
    if (distance_squared(point_a, point_b) > kEpsilon * kEpsilon) {
      wm.normal = point_b - point_a;
      normalize(wm.normal);
    }
    const Vec2 c_a = point_a + radius_a * wm.normal;
    const Vec2 c_b = point_b - radius_b * wm.normal;
    wm.points[0] = 0.5f * (c_a + c_b);
  } else if (m.type == ManifoldType::face_a) {
    wm.normal = mul(xf_a.q, m.local_normal);
    const Vec2 plane_point = mul(xf_a, m.local_point);
    for (int i = 0; i < m.point_count; ++i) {
      const Vec2 clip_point = mul(xf_b, m.points[i].local_point);
      const Vec2 c_a =
          clip_point + (radius_a - dot(clip_point - plane_point, wm.normal)) * wm.normal;
      const Vec2 c_b = clip_point - radius_b * wm.normal;
      wm.points[i] = 0.5f * (c_a + c_b);
    }
  } else {
    wm.normal = mul(xf_b.q, m.local_normal);
    const Vec2 plane_point = mul(xf_b, m.local_point);
    for (int i = 0; i < m.point_count; ++i) {
      const Vec2 clip_point = mul(xf_a, m.points[i].local_point);
      const Vec2 c_b =
          clip_point + (radius_b - dot(clip_point - plane_point, wm.normal)) * wm.normal;
      const Vec2 c_a = clip_point - radius_a * wm.normal;
      wm.points[i] = 0.5f * (c_a + c_b);
    }
    wm.normal = -wm.normal;  // from A to B
  }
  return wm;
}

// ---------------------------------------------------------------------------------------------
// b2_distance.h/.cpp: GJK distance between the two shapes' cores (radii not applied).

// b2_distance.h, b2DistanceProxy: a polygon's vertices and skin, or a circle's centre and radius
struct DistanceProxy {
  const Vec2* vertices = nullptr;
  int count = 0;
  float radius = 0.0f;

  // b2_distance.h, b2DistanceProxy::GetSupport: the vertex furthest along d.
  int support(Vec2 d) const {
    int best_index = 0;
    float best_value = dot(vertices[0], d);
    for (int i = 1; i < count; ++i) {
      const float value = dot(vertices[i], d);
      if (value > best_value) {
        best_index = i;
        best_value = value;
      }
    }
    return best_index;
  }
};

// b2_distance.cpp, b2DistanceProxy::Set (the circle and polygon cases)
DistanceProxy proxy_of(const Shape& s) {
  if (s.is_circle) return {&s.circle.p, 1, s.circle.radius};
  return {s.polygon.vertices, s.polygon.count, s.polygon.radius};
}

// b2_distance.h, b2SimplexCache: the last simplex's vertex indices and size metric.
struct SimplexCache {
  float metric = 0.0f;
  int count = 0;
  int index_a[3] = {0, 0, 0};
  int index_b[3] = {0, 0, 0};
};

// b2_distance.cpp, b2SimplexVertex: a Minkowski-difference point w = wB - wA.
struct SimplexVertex {
  Vec2 w_a, w_b, w;
  float a = 0.0f;  // barycentric coordinate of the closest point
  int index_a = 0, index_b = 0;
};

// b2_distance.cpp, b2Simplex
struct Simplex {
  SimplexVertex v[3];
  int count = 0;

  // b2_distance.cpp, b2Simplex::ReadCache: restart from the cached vertices unless their metric
  // changed by more than 2x; else from the two first vertices.
  void read_cache(const SimplexCache& cache, const DistanceProxy& pa, const Xf& xa,
                  const DistanceProxy& pb, const Xf& xb) {
    count = cache.count;
    for (int i = 0; i < count; ++i) {
      SimplexVertex& s = v[i];
      s.index_a = cache.index_a[i];
      s.index_b = cache.index_b[i];
      s.w_a = mul(xa, pa.vertices[s.index_a]);
      s.w_b = mul(xb, pb.vertices[s.index_b]);
      s.w = s.w_b - s.w_a;
      s.a = 0.0f;
    }
    if (count > 1) {
      const float metric1 = cache.metric;
      const float metric2 = metric();
      if (metric2 < 0.5f * metric1 || 2.0f * metric1 < metric2 || metric2 < kEpsilon) count = 0;
    }
    if (count == 0) {
      SimplexVertex& s = v[0];
      s.index_a = 0;
      s.index_b = 0;
      s.w_a = mul(xa, pa.vertices[0]);
      s.w_b = mul(xb, pb.vertices[0]);
      s.w = s.w_b - s.w_a;
      s.a = 1.0f;
      count = 1;
    }
  }

  // b2_distance.cpp, b2Simplex::WriteCache
  void write_cache(SimplexCache& cache) const {
    cache.metric = metric();
    cache.count = count;
    for (int i = 0; i < count; ++i) {
      cache.index_a[i] = v[i].index_a;
      cache.index_b[i] = v[i].index_b;
    }
  }

  // b2_distance.cpp, b2Simplex::GetSearchDirection: towards the origin.
  Vec2 search_direction() const {
    if (count == 1) return -v[0].w;
    const Vec2 e12 = v[1].w - v[0].w;
    const float sgn = cross(e12, -v[0].w);
    return sgn > 0.0f ? cross(1.0f, e12) : cross(e12, 1.0f);
  }

  // b2_distance.cpp, b2Simplex::GetWitnessPoints
  void witness_points(Vec2& pa, Vec2& pb) const {
    if (count == 1) {
      pa = v[0].w_a;
      pb = v[0].w_b;
    } else if (count == 2) {
      pa = v[0].a * v[0].w_a + v[1].a * v[1].w_a;
      pb = v[0].a * v[0].w_b + v[1].a * v[1].w_b;
    } else {
      pa = v[0].a * v[0].w_a + v[1].a * v[1].w_a + v[2].a * v[2].w_a;
      pb = pa;
    }
  }

  // b2_distance.cpp, b2Simplex::GetMetric: 0, the segment's length or the triangle's area x2.
  float metric() const {
    if (count == 2) return distance(v[0].w, v[1].w);
    if (count == 3) return cross(v[1].w - v[0].w, v[2].w - v[0].w);
    return 0.0f;
  }

  void solve2();
  void solve3();
};

// b2_distance.cpp, b2Simplex::Solve2: the closest point of segment w1 w2 to the origin, as
// barycentric weights (a1, a2) = (w2.e12, -w1.e12)/|e12|^2; an end when the other weight <= 0.
void Simplex::solve2() {
  const Vec2 w1 = v[0].w;
  const Vec2 w2 = v[1].w;
  const Vec2 e12 = w2 - w1;
  const float d12_2 = -dot(w1, e12);
  if (d12_2 <= 0.0f) {
    v[0].a = 1.0f;
    count = 1;
    return;
  }
  const float d12_1 = dot(w2, e12);
  if (d12_1 <= 0.0f) {
    v[1].a = 1.0f;
    count = 1;
    v[0] = v[1];
    return;
  }
  const float inv_d12 = 1.0f / (d12_1 + d12_2);
  v[0].a = d12_1 * inv_d12;
  v[1].a = d12_2 * inv_d12;
  count = 2;
}

// b2_distance.cpp, b2Simplex::Solve3: the Voronoi region of triangle w1 w2 w3 holding the origin
// (a vertex, an edge, or the inside), by the edges' and the triangle's barycentric numerators.
void Simplex::solve3() {
  const Vec2 w1 = v[0].w, w2 = v[1].w, w3 = v[2].w;
  const Vec2 e12 = w2 - w1;
  const float d12_1 = dot(w2, e12);
  const float d12_2 = -dot(w1, e12);
  const Vec2 e13 = w3 - w1;
  const float d13_1 = dot(w3, e13);
  const float d13_2 = -dot(w1, e13);
  const Vec2 e23 = w3 - w2;
  const float d23_1 = dot(w3, e23);
  const float d23_2 = -dot(w2, e23);
  const float n123 = cross(e12, e13);
  const float d123_1 = n123 * cross(w2, w3);
  const float d123_2 = n123 * cross(w3, w1);
  const float d123_3 = n123 * cross(w1, w2);

  if (d12_2 <= 0.0f && d13_2 <= 0.0f) {  // w1
    v[0].a = 1.0f;
    count = 1;
    return;
  }
  if (d12_1 > 0.0f && d12_2 > 0.0f && d123_3 <= 0.0f) {  // e12
    const float inv_d12 = 1.0f / (d12_1 + d12_2);
    v[0].a = d12_1 * inv_d12;
    v[1].a = d12_2 * inv_d12;
    count = 2;
    return;
  }
  if (d13_1 > 0.0f && d13_2 > 0.0f && d123_2 <= 0.0f) {  // e13
    const float inv_d13 = 1.0f / (d13_1 + d13_2);
    v[0].a = d13_1 * inv_d13;
    v[2].a = d13_2 * inv_d13;
    count = 2;
    v[1] = v[2];
    return;
  }
  if (d12_1 <= 0.0f && d23_2 <= 0.0f) {  // w2
    v[1].a = 1.0f;
    count = 1;
    v[0] = v[1];
    return;
  }
  if (d13_1 <= 0.0f && d23_1 <= 0.0f) {  // w3
    v[2].a = 1.0f;
    count = 1;
    v[0] = v[2];
    return;
  }
  if (d23_1 > 0.0f && d23_2 > 0.0f && d123_1 <= 0.0f) {  // e23
    const float inv_d23 = 1.0f / (d23_1 + d23_2);
    v[1].a = d23_1 * inv_d23;
    v[2].a = d23_2 * inv_d23;
    count = 2;
    v[0] = v[2];
    return;
  }
  const float inv_d123 = 1.0f / (d123_1 + d123_2 + d123_3);  // inside
  v[0].a = d123_1 * inv_d123;
  v[1].a = d123_2 * inv_d123;
  v[2].a = d123_3 * inv_d123;
  count = 3;
}

// b2_distance.cpp, b2Distance (useRadii = false, as b2TimeOfImpact calls it): GJK from the cached
// simplex; each iteration reduces the simplex to the closest feature and adds the support point
// against the direction to the origin, until the origin is enclosed, the direction vanishes or a
// support point repeats (20 iterations at most). Returns the cores' distance.
float gjk_distance(SimplexCache& cache, const DistanceProxy& pa, const Xf& xa,
                   const DistanceProxy& pb, const Xf& xb) {
  Simplex simplex;
  simplex.read_cache(cache, pa, xa, pb, xb);
  const int k_max_iters = 20;
  int save_a[3], save_b[3];
  int iter = 0;
  while (iter < k_max_iters) {
    const int save_count = simplex.count;
    for (int i = 0; i < save_count; ++i) {
      save_a[i] = simplex.v[i].index_a;
      save_b[i] = simplex.v[i].index_b;
    }
    if (simplex.count == 2) {
      simplex.solve2();
    } else if (simplex.count == 3) {
      simplex.solve3();
    }
    if (simplex.count == 3) break;  // the origin is inside the triangle
    const Vec2 d = simplex.search_direction();
    if (dot(d, d) < kEpsilon * kEpsilon) break;  // b2Vec2::LengthSquared
    SimplexVertex& vertex = simplex.v[simplex.count];
    vertex.index_a = pa.support(mul_t(xa.q, -d));
    vertex.w_a = mul(xa, pa.vertices[vertex.index_a]);
    vertex.index_b = pb.support(mul_t(xb.q, d));
    vertex.w_b = mul(xb, pb.vertices[vertex.index_b]);
    vertex.w = vertex.w_b - vertex.w_a;
    ++iter;
    bool duplicate = false;
    for (int i = 0; i < save_count; ++i) {
      if (vertex.index_a == save_a[i] && vertex.index_b == save_b[i]) {
        duplicate = true;
        break;
      }
    }
    if (duplicate) break;
    ++simplex.count;
  }
  Vec2 point_a, point_b;
  simplex.witness_points(point_a, point_b);
  simplex.write_cache(cache);
  return distance(point_a, point_b);
}

// ---------------------------------------------------------------------------------------------
// b2_time_of_impact.cpp: conservative advancement along the two sweeps.

// b2_time_of_impact.cpp, b2SeparationFunction: the separation along an axis fixed by the last GJK
// simplex (two points, a face of A or a face of B), as a function of the sweep time.
struct SeparationFunction {
  enum class Type { points, face_a, face_b };
  const DistanceProxy* proxy_a = nullptr;
  const DistanceProxy* proxy_b = nullptr;
  Sweep sweep_a, sweep_b;
  Type type = Type::points;
  Vec2 local_point, axis;

  float initialize(const SimplexCache& cache, const DistanceProxy& pa, const Sweep& sa,
                   const DistanceProxy& pb, const Sweep& sb, float t1);
  float find_min_separation(int& index_a, int& index_b, float t) const;
  float evaluate(int index_a, int index_b, float t) const;

 private:
  float face_separation(const DistanceProxy& face, const Xf& xf_face, const int* i, Vec2 other,
                        const Xf& xf_other);
};

// b2_time_of_impact.cpp, b2SeparationFunction::Initialize: the axis at t1 and the separation on it.
float SeparationFunction::initialize(const SimplexCache& cache, const DistanceProxy& pa,
                                     const Sweep& sa, const DistanceProxy& pb, const Sweep& sb,
                                     float t1) {
  proxy_a = &pa;
  proxy_b = &pb;
  sweep_a = sa;
  sweep_b = sb;
  const Xf xf_a = sweep_a.transform(t1);
  const Xf xf_b = sweep_b.transform(t1);
  if (cache.count == 1) {  // the axis joins the two witness points
    type = Type::points;
    const Vec2 point_a = mul(xf_a, pa.vertices[cache.index_a[0]]);
    const Vec2 point_b = mul(xf_b, pb.vertices[cache.index_b[0]]);
    axis = point_b - point_a;
    return normalize(axis);
  }
  if (cache.index_a[0] == cache.index_a[1]) {  // two points on B, one on A: B's face normal
    type = Type::face_b;
    return face_separation(pb, xf_b, cache.index_b, pa.vertices[cache.index_a[0]], xf_a);
  }
  type = Type::face_a;  // two points on A: A's face normal
  return face_separation(pa, xf_a, cache.index_a, pb.vertices[cache.index_b[0]], xf_b);
}

// The face case of Initialize, for the face on `face` (its vertices i[0], i[1]) and the point
// `other` of the other proxy: the axis is the face's normal (in the face's frame), local_point
// the face's midpoint, and the separation the other point's distance from it, the axis flipped to
// make it positive.
float SeparationFunction::face_separation(const DistanceProxy& face, const Xf& xf_face,
                                          const int* i, Vec2 other, const Xf& xf_other) {
  const Vec2 local_1 = face.vertices[i[0]];
  const Vec2 local_2 = face.vertices[i[1]];
  axis = cross(local_2 - local_1, 1.0f);
  normalize(axis);
  const Vec2 normal = mul(xf_face.q, axis);
  local_point = 0.5f * (local_1 + local_2);
  const Vec2 point_face = mul(xf_face, local_point);
  const Vec2 point_other = mul(xf_other, other);
  float s = dot(point_other - point_face, normal);
  if (s < 0.0f) {
    axis = -axis;
    s = -s;
  }
  return s;
}

// b2_time_of_impact.cpp, b2SeparationFunction::FindMinSeparation: the deepest points along the
// axis at time t (-1 for the face side) and their separation.
float SeparationFunction::find_min_separation(int& index_a, int& index_b, float t) const {
  const Xf xf_a = sweep_a.transform(t);
  const Xf xf_b = sweep_b.transform(t);
  if (type == Type::points) {
    const Vec2 axis_a = mul_t(xf_a.q, axis);
    const Vec2 axis_b = mul_t(xf_b.q, -axis);
    index_a = proxy_a->support(axis_a);
    index_b = proxy_b->support(axis_b);
    const Vec2 point_a = mul(xf_a, proxy_a->vertices[index_a]);
    const Vec2 point_b = mul(xf_b, proxy_b->vertices[index_b]);
    return dot(point_b - point_a, axis);
  }
  if (type == Type::face_a) {
    const Vec2 normal = mul(xf_a.q, axis);
    const Vec2 point_a = mul(xf_a, local_point);
    const Vec2 axis_b = mul_t(xf_b.q, -normal);
    index_a = -1;
    index_b = proxy_b->support(axis_b);
    const Vec2 point_b = mul(xf_b, proxy_b->vertices[index_b]);
    return dot(point_b - point_a, normal);
  }
  const Vec2 normal = mul(xf_b.q, axis);
  const Vec2 point_b = mul(xf_b, local_point);
  const Vec2 axis_a = mul_t(xf_a.q, -normal);
  index_b = -1;
  index_a = proxy_a->support(axis_a);
  const Vec2 point_a = mul(xf_a, proxy_a->vertices[index_a]);
  return dot(point_a - point_b, normal);
}

// b2_time_of_impact.cpp, b2SeparationFunction::Evaluate: the same points' separation at time t.
float SeparationFunction::evaluate(int index_a, int index_b, float t) const {
  const Xf xf_a = sweep_a.transform(t);
  const Xf xf_b = sweep_b.transform(t);
  if (type == Type::points) {
    const Vec2 point_a = mul(xf_a, proxy_a->vertices[index_a]);
    const Vec2 point_b = mul(xf_b, proxy_b->vertices[index_b]);
    return dot(point_b - point_a, axis);
  }
  if (type == Type::face_a) {
    const Vec2 normal = mul(xf_a.q, axis);
    const Vec2 point_a = mul(xf_a, local_point);
    const Vec2 point_b = mul(xf_b, proxy_b->vertices[index_b]);
    return dot(point_b - point_a, normal);
  }
  const Vec2 normal = mul(xf_b.q, axis);
  const Vec2 point_b = mul(xf_b, local_point);
  const Vec2 point_a = mul(xf_a, proxy_a->vertices[index_a]);
  return dot(point_a - point_b, normal);
}

// b2_time_of_impact.h, b2TOIOutput::State
enum class ToiState { unknown, failed, overlapped, touching, separated };
struct ToiOutput {
  ToiState state = ToiState::unknown;
  float t = 0.0f;
};

// b2_time_of_impact.cpp, b2TimeOfImpact, inner root finder: the time in [a1, a2] where the
// witness points' separation is within tolerance of target, alternating bisection and the secant
// rule (50 iterations at most).
float toi_root(const SeparationFunction& fcn, int index_a, int index_b, float t1, float t2,
               float s1, float s2, float target, float tolerance) {
  int root_iter_count = 0;
  float a1 = t1, a2 = t2;
  for (;;) {
    float t;
    if (root_iter_count & 1) {
      t = a1 + (target - s1) * (a2 - a1) / (s2 - s1);
    } else {
      t = 0.5f * (a1 + a2);
    }
    ++root_iter_count;
    const float s = fcn.evaluate(index_a, index_b, t);
    if (abs_f(s - target) < tolerance) return t;  // t2 takes it
    if (s > target) {
      a1 = t;
      s1 = s;
    } else {
      a2 = t;
      s2 = s;
    }
    if (root_iter_count == 50) return t2;
  }
}

// b2_time_of_impact.cpp, b2TimeOfImpact: the first time in [0, tMax] at which the cores come
// within target = max(slop, rA + rB - 3 slop) of each other (within tolerance = slop/4). Each outer
// iteration takes GJK's axis at t1 and pushes t2 back along it until the deepest points on it are
// at target; that t2 becomes t1.
ToiOutput time_of_impact(const DistanceProxy& pa, const DistanceProxy& pb, Sweep sweep_a,
                         Sweep sweep_b, float t_max) {
  ToiOutput output;
  output.state = ToiState::unknown;
  output.t = t_max;
  sweep_a.normalize();
  sweep_b.normalize();
  const float total_radius = pa.radius + pb.radius;
  const float target = max_f(kLinearSlop, total_radius - 3.0f * kLinearSlop);
  const float tolerance = 0.25f * kLinearSlop;
  float t1 = 0.0f;
  const int k_max_iterations = 20;
  int iter = 0;
  SimplexCache cache;
  cache.count = 0;
  for (;;) {
    const Xf xf_a = sweep_a.transform(t1);
    const Xf xf_b = sweep_b.transform(t1);
    const float dist = gjk_distance(cache, pa, xf_a, pb, xf_b);
    if (dist <= 0.0f) {
      output = {ToiState::overlapped, 0.0f};
      break;
    }
    if (dist < target + tolerance) {
      output = {ToiState::touching, t1};
      break;
    }
    SeparationFunction fcn;
    fcn.initialize(cache, pa, sweep_a, pb, sweep_b, t1);
    bool done = false;
    float t2 = t_max;
    int push_back_iter = 0;
    for (;;) {
      int index_a = 0, index_b = 0;
      float s2 = fcn.find_min_separation(index_a, index_b, t2);
      if (s2 > target + tolerance) {  // separated at the end
        output = {ToiState::separated, t_max};
        done = true;
        break;
      }
      if (s2 > target - tolerance) {  // at target at t2: advance
        t1 = t2;
        break;
      }
      const float s1 = fcn.evaluate(index_a, index_b, t1);
      if (s1 < target - tolerance) {  // overlapped at t1: the root finder ran out
        output = {ToiState::failed, t1};
        done = true;
        break;
      }
      if (s1 <= target + tolerance) {  // touching at t1
        output = {ToiState::touching, t1};
        done = true;
        break;
      }
      t2 = toi_root(fcn, index_a, index_b, t1, t2, s1, s2, target, tolerance);
      ++push_back_iter;
      if (push_back_iter == kMaxPolygonVertices) break;
    }
    ++iter;
    if (done) break;
    if (iter == k_max_iterations) {
      output = {ToiState::failed, t1};
      break;
    }
  }
  return output;
}

// ---------------------------------------------------------------------------------------------
// b2_body.h/.cpp, b2_fixture.cpp, b2_dynamic_tree.cpp: the bodies, their fixture and its proxy.

struct Body {
  bool is_static = false;
  bool awake = false;   // b2Body::e_awakeFlag (never set on a static body)
  bool island = false;  // b2Body::e_islandFlag
  int island_index = 0;
  Xf xf;        // m_xf: GetPosition() is xf.p
  Sweep sweep;  // GetAngle() is sweep.a
  Vec2 v;
  float w = 0.0f;
  Vec2 force;  // always 0 (no user forces); kept for b2Island::Solve's sum
  float torque = 0.0f;
  float gravity_scale = 1.0f;
  float mass = 0.0f, inv_mass = 0.0f, I = 0.0f, inv_I = 0.0f;
  float linear_damping = 0.0f, angular_damping = 0.0f;
  // The one fixture.
  Shape shape;
  float friction = 0.0f, restitution = 0.0f, restitution_threshold = kRestitutionThreshold;
  // Its broad-phase proxy: the fat AABB in the tree and whether it is in the move buffer.
  Aabb fat;
  bool moved = false;
};

// b2_body.cpp, b2Body::b2Body
Body create_body(const Box2dBox& def) {
  Body b;
  b.is_static = def.is_static;
  b.awake = !def.is_static;
  b.xf.p = {def.x, def.y};
  b.xf.q = rot(def.angle);
  b.sweep.local_center = {0.0f, 0.0f};
  b.sweep.c0 = b.xf.p;
  b.sweep.c = b.xf.p;
  b.sweep.a0 = def.angle;
  b.sweep.a = def.angle;
  b.sweep.alpha0 = 0.0f;
  b.v = {def.vx, def.vy};
  b.w = def.w;
  b.linear_damping = def.linear_damping;
  b.angular_damping = def.angular_damping;
  return b;
}

// b2_body.cpp, b2Body::ResetMassData: mass and inertia from the fixture, inertia moved to the
// centre of mass, the sweep moved onto it and the velocity corrected for the shift (w x dc).
void reset_mass_data(Body& b, float density) {
  b.mass = 0.0f;
  b.inv_mass = 0.0f;
  b.I = 0.0f;
  b.inv_I = 0.0f;
  b.sweep.local_center = {0.0f, 0.0f};
  if (b.is_static) {
    b.sweep.c0 = b.xf.p;
    b.sweep.c = b.xf.p;
    b.sweep.a0 = b.sweep.a;
    return;
  }
  Vec2 local_center{0.0f, 0.0f};
  const MassData m = compute_mass(b.shape, density);
  b.mass += m.mass;
  local_center += m.mass * m.center;
  b.I += m.I;
  if (b.mass > 0.0f) {
    b.inv_mass = 1.0f / b.mass;
    local_center *= b.inv_mass;
  }
  if (b.I > 0.0f) {
    b.I -= b.mass * dot(local_center, local_center);
    b.inv_I = 1.0f / b.I;
  } else {
    b.I = 0.0f;
    b.inv_I = 0.0f;
  }
  const Vec2 old_center = b.sweep.c;
  b.sweep.local_center = local_center;
  b.sweep.c0 = b.sweep.c = mul(b.xf, b.sweep.local_center);
  b.v += cross(b.w, b.sweep.c - old_center);
}

// b2_body.cpp, b2Body::CreateFixture with b2_fixture.cpp, b2Fixture::CreateProxies and
// b2_dynamic_tree.cpp, b2DynamicTree::CreateProxy: the box or circle, its fattened AABB now, in
// the move buffer; the mass set-up when the fixture has density.
void create_fixture(Body& b, const Box2dBox& def) {
  b.shape.is_circle = def.radius > 0.0f;
  if (b.shape.is_circle) {
    b.shape.circle = {{0.0f, 0.0f}, def.radius};
  } else {
    b.shape.polygon = set_as_box(def.hx, def.hy);
  }
  b.friction = def.friction;
  b.restitution = def.restitution;
  const Aabb aabb = compute_aabb(b.shape, b.xf);
  const Vec2 r{kAabbExtension, kAabbExtension};
  b.fat = {aabb.lower - r, aabb.upper + r};
  b.moved = true;
  if (def.density > 0.0f) reset_mass_data(b, def.density);
}

// b2_body.h, b2Body::SynchronizeTransform: the body frame from the sweep's end.
void synchronize_transform(Body& b) {
  b.xf.q = rot(b.sweep.a);
  b.xf.p = b.sweep.c - mul(b.xf.q, b.sweep.local_center);
}

// b2_body.h, b2Body::Advance: the sweep's start and the body moved to time alpha.
void advance_body(Body& b, float alpha) {
  b.sweep.advance(alpha);
  b.sweep.c = b.sweep.c0;
  b.sweep.a = b.sweep.a0;
  synchronize_transform(b);
}

// b2_dynamic_tree.cpp, b2DynamicTree::MoveProxy (with b2BroadPhase::MoveProxy's buffering): a
// new fat AABB (margin, plus 4x the displacement ahead) unless the tree's still holds the swept
// AABB and is not more than 4 margins too large.
void move_proxy(Body& b, const Aabb& aabb, Vec2 displacement) {
  const Vec2 r{kAabbExtension, kAabbExtension};
  Aabb fat{aabb.lower - r, aabb.upper + r};
  const Vec2 d = kAabbMultiplier * displacement;
  if (d.x < 0.0f) {
    fat.lower.x += d.x;
  } else {
    fat.upper.x += d.x;
  }
  if (d.y < 0.0f) {
    fat.lower.y += d.y;
  } else {
    fat.upper.y += d.y;
  }
  if (contains(b.fat, aabb)) {
    const Aabb huge{fat.lower - 4.0f * r, fat.upper + 4.0f * r};
    if (contains(huge, b.fat)) return;
  }
  b.fat = fat;
  b.moved = true;
}

// b2_body.cpp, b2Body::SynchronizeFixtures and b2_fixture.cpp, b2Fixture::Synchronize: the
// proxy follows the AABB swept from the sweep's start (c0, a0) to the body's frame.
void synchronize_fixtures(Body& b) {
  Xf xf1 = b.xf;
  if (b.awake) {
    xf1.q = rot(b.sweep.a0);
    xf1.p = b.sweep.c0 - mul(xf1.q, b.sweep.local_center);
  }
  const Aabb aabb1 = compute_aabb(b.shape, xf1);
  const Aabb aabb2 = compute_aabb(b.shape, b.xf);
  const Aabb swept = combine(aabb1, aabb2);
  const Vec2 displacement = center(aabb2) - center(aabb1);
  move_proxy(b, swept, displacement);
}

// ---------------------------------------------------------------------------------------------
// b2_contact.h/.cpp: the one contact between the two fixtures (A and B as World::body_a/body_b).

struct Contact {
  Manifold manifold;
  bool enabled = true;    // e_enabledFlag
  bool touching = false;  // e_touchingFlag
  bool island = false;    // e_islandFlag
  bool toi_flag = false;  // e_toiFlag: toi holds this step's time of impact
  float toi = 0.0f;
  int toi_count = 0;
  float friction = 0.0f, restitution = 0.0f, threshold = 0.0f;
  float tangent_speed = 0.0f;
};

// b2_contact.cpp, b2Contact::b2Contact with b2_contact.h's mixing laws: friction sqrt(f1 f2),
// the larger restitution, the smaller restitution threshold.
Contact make_contact(const Body& a, const Body& b) {
  Contact c;
  c.friction = std::sqrt(a.friction * b.friction);
  c.restitution = a.restitution > b.restitution ? a.restitution : b.restitution;
  c.threshold = a.restitution_threshold < b.restitution_threshold ? a.restitution_threshold
                                                                  : b.restitution_threshold;
  return c;
}

// b2_polygon_contact.cpp, b2_polygon_circle_contact.cpp, b2_circle_contact.cpp, the contacts'
// Evaluate: the manifold function of the two shapes (a polygon with a circle: A is the polygon).
void evaluate(Manifold& manifold, const Shape& a, const Xf& xf_a, const Shape& b, const Xf& xf_b) {
  if (!a.is_circle && !b.is_circle) {
    collide_polygons(manifold, a.polygon, xf_a, b.polygon, xf_b);
  } else if (!a.is_circle) {
    collide_polygon_and_circle(manifold, a.polygon, xf_a, b.circle, xf_b);
  } else if (b.is_circle) {
    collide_circles(manifold, a.circle, xf_a, b.circle, xf_b);
  } else {
    throw std::logic_error("box2d_replay: a circle as fixture A of a polygon");
  }
}

// b2_contact.cpp, b2Contact::Update: the new manifold at the bodies' frames; a point whose
// feature id was in the old manifold takes over its impulses (warm starting), others start at 0.
void update_contact(Contact& c, const Body& a, const Body& b) {
  const Manifold old = c.manifold;
  c.enabled = true;
  evaluate(c.manifold, a.shape, a.xf, b.shape, b.xf);
  for (int i = 0; i < c.manifold.point_count; ++i) {
    ManifoldPoint& mp2 = c.manifold.points[i];
    mp2.normal_impulse = 0.0f;
    mp2.tangent_impulse = 0.0f;
    for (int j = 0; j < old.point_count; ++j) {
      const ManifoldPoint& mp1 = old.points[j];
      if (same_key(mp1.id, mp2.id)) {
        mp2.normal_impulse = mp1.normal_impulse;
        mp2.tangent_impulse = mp1.tangent_impulse;
        break;
      }
    }
  }
  c.touching = c.manifold.point_count > 0;
}

// ---------------------------------------------------------------------------------------------
// b2_contact_solver.cpp: sequential impulses on the island's contact.

struct Position {
  Vec2 c;
  float a = 0.0f;
};
struct Velocity {
  Vec2 v;
  float w = 0.0f;
};

// b2_time_step.h, b2TimeStep
struct TimeStep {
  float dt = 0.0f, inv_dt = 0.0f, dt_ratio = 0.0f;
  int velocity_iterations = 0, position_iterations = 0;
  bool warm_starting = true;
};

struct VelocityPoint {
  Vec2 r_a, r_b;  // from each centre of mass to the point
  float normal_impulse = 0.0f, tangent_impulse = 0.0f;
  float normal_mass = 0.0f, tangent_mass = 0.0f, velocity_bias = 0.0f;
};

// b2_contact_solver.h, b2ContactVelocityConstraint
struct VelocityConstraint {
  VelocityPoint points[2];
  Vec2 normal;
  Mat22 normal_mass, K;
  int index_a = 0, index_b = 0;
  float inv_mass_a = 0.0f, inv_mass_b = 0.0f, inv_i_a = 0.0f, inv_i_b = 0.0f;
  float friction = 0.0f, restitution = 0.0f, threshold = 0.0f, tangent_speed = 0.0f;
  int point_count = 0;
};

// b2_contact_solver.cpp, b2ContactPositionConstraint
struct PositionConstraint {
  Vec2 local_points[2];
  Vec2 local_normal, local_point;
  int index_a = 0, index_b = 0;
  float inv_mass_a = 0.0f, inv_mass_b = 0.0f;
  Vec2 local_center_a, local_center_b;
  float inv_i_a = 0.0f, inv_i_b = 0.0f;
  ManifoldType type = ManifoldType::face_a;
  float radius_a = 0.0f, radius_b = 0.0f;
  int point_count = 0;
};

// The two bodies' velocities while one constraint is solved (b2ContactSolver's locals).
struct PairVelocity {
  Vec2 v_a;
  float w_a = 0.0f;
  Vec2 v_b;
  float w_b = 0.0f;
};

// b2_contact_solver.cpp, the relative velocity of B against A at a point: vB + wB x rB - vA -
// wA x rA, summed in that order.
Vec2 relative_velocity(const PairVelocity& u, const VelocityPoint& p) {
  return u.v_b + cross(u.w_b, p.r_b) - u.v_a - cross(u.w_a, p.r_a);
}

// The frame of a body from its position-solver state: b2ContactSolver's xfA/xfB.
Xf frame_of(const Position& p, Vec2 local_center) {
  Xf xf;
  xf.q = rot(p.a);
  xf.p = p.c - mul(xf.q, local_center);
  return xf;
}

class ContactSolver {
 public:
  ContactSolver(const TimeStep& step, Contact* contact, const Body& a, const Body& b,
                Position* positions, Velocity* velocities);
  void initialize_velocity_constraints();
  void warm_start();
  void solve_velocity_constraints();
  void store_impulses();
  bool solve_position_constraints();
  bool solve_toi_position_constraints(int toi_index_a, int toi_index_b);

 private:
  PairVelocity load() const;
  void save(const PairVelocity& u);
  void prepare_block_solver();
  void solve_friction(PairVelocity& u);
  void solve_normal_points(PairVelocity& u);
  void solve_normal_block(PairVelocity& u);
  void apply_block(PairVelocity& u, Vec2 x, Vec2 a);
  float solve_positions(float baumgarte, float m_a, float i_a, float m_b, float i_b);

  TimeStep step_;
  Contact* contact_;  // null: no contact in the island, nothing to solve
  Position* positions_;
  Velocity* velocities_;
  VelocityConstraint vc_;
  PositionConstraint pc_;
};

// b2_contact_solver.cpp, b2ContactSolver::b2ContactSolver: the position-independent parts, the
// warm-start impulses scaled by dt/dt0 (dtRatio).
ContactSolver::ContactSolver(const TimeStep& step, Contact* contact, const Body& a, const Body& b,
                             Position* positions, Velocity* velocities)
    : step_(step), contact_(contact), positions_(positions), velocities_(velocities) {
  if (contact_ == nullptr) return;
  const Manifold& m = contact_->manifold;
  vc_.friction = contact_->friction;
  vc_.restitution = contact_->restitution;
  vc_.threshold = contact_->threshold;
  vc_.tangent_speed = contact_->tangent_speed;
  vc_.index_a = a.island_index;
  vc_.index_b = b.island_index;
  vc_.inv_mass_a = a.inv_mass;
  vc_.inv_mass_b = b.inv_mass;
  vc_.inv_i_a = a.inv_I;
  vc_.inv_i_b = b.inv_I;
  vc_.point_count = m.point_count;
  pc_.index_a = a.island_index;
  pc_.index_b = b.island_index;
  pc_.inv_mass_a = a.inv_mass;
  pc_.inv_mass_b = b.inv_mass;
  pc_.local_center_a = a.sweep.local_center;
  pc_.local_center_b = b.sweep.local_center;
  pc_.inv_i_a = a.inv_I;
  pc_.inv_i_b = b.inv_I;
  pc_.local_normal = m.local_normal;
  pc_.local_point = m.local_point;
  pc_.point_count = m.point_count;
  pc_.radius_a = a.shape.radius();
  pc_.radius_b = b.shape.radius();
  pc_.type = m.type;
  for (int j = 0; j < m.point_count; ++j) {
    VelocityPoint& vcp = vc_.points[j];
    if (step_.warm_starting) {
      vcp.normal_impulse = step_.dt_ratio * m.points[j].normal_impulse;
      vcp.tangent_impulse = step_.dt_ratio * m.points[j].tangent_impulse;
    }
    pc_.local_points[j] = m.points[j].local_point;
  }
}

PairVelocity ContactSolver::load() const {
  const Velocity& a = velocities_[vc_.index_a];
  const Velocity& b = velocities_[vc_.index_b];
  return {a.v, a.w, b.v, b.w};
}

void ContactSolver::save(const PairVelocity& u) {
  velocities_[vc_.index_a] = {u.v_a, u.w_a};
  velocities_[vc_.index_b] = {u.v_b, u.w_b};
}

// b2_contact_solver.cpp, b2ContactSolver::InitializeVelocityConstraints: per point the arms, the
// normal and tangent effective masses 1/(mA + mB + iA (rA x n)^2 + iB (rB x n)^2), and the
// restitution bias for approach faster than the threshold; then the block solver's K.
void ContactSolver::initialize_velocity_constraints() {
  if (contact_ == nullptr) return;
  const float m_a = vc_.inv_mass_a, m_b = vc_.inv_mass_b;
  const float i_a = vc_.inv_i_a, i_b = vc_.inv_i_b;
  const Position& pa = positions_[vc_.index_a];
  const Position& pb = positions_[vc_.index_b];
  const PairVelocity u = load();
  const Xf xf_a = frame_of(pa, pc_.local_center_a);
  const Xf xf_b = frame_of(pb, pc_.local_center_b);
  const WorldManifold wm =
      world_manifold(contact_->manifold, xf_a, pc_.radius_a, xf_b, pc_.radius_b);
  vc_.normal = wm.normal;
  for (int j = 0; j < vc_.point_count; ++j) {
    VelocityPoint& vcp = vc_.points[j];
    vcp.r_a = wm.points[j] - pa.c;
    vcp.r_b = wm.points[j] - pb.c;
    const float rn_a = cross(vcp.r_a, vc_.normal);
    const float rn_b = cross(vcp.r_b, vc_.normal);
    const float k_normal = m_a + m_b + i_a * rn_a * rn_a + i_b * rn_b * rn_b;
    vcp.normal_mass = k_normal > 0.0f ? 1.0f / k_normal : 0.0f;
    const Vec2 tangent = cross(vc_.normal, 1.0f);
    const float rt_a = cross(vcp.r_a, tangent);
    const float rt_b = cross(vcp.r_b, tangent);
    const float k_tangent = m_a + m_b + i_a * rt_a * rt_a + i_b * rt_b * rt_b;
    vcp.tangent_mass = k_tangent > 0.0f ? 1.0f / k_tangent : 0.0f;
    vcp.velocity_bias = 0.0f;
    const float v_rel = dot(vc_.normal, relative_velocity(u, vcp));
    if (v_rel < -vc_.threshold) vcp.velocity_bias = -vc_.restitution * v_rel;
  }
  if (vc_.point_count == 2) prepare_block_solver();
}

// b2_contact_solver.cpp, b2ContactSolver::InitializeVelocityConstraints, block part: the 2x2
// normal mass matrix K and its inverse, unless K's condition number would pass 1000 (then the
// second point is dropped from the solve).
void ContactSolver::prepare_block_solver() {
  const float m_a = vc_.inv_mass_a, m_b = vc_.inv_mass_b;
  const float i_a = vc_.inv_i_a, i_b = vc_.inv_i_b;
  const VelocityPoint& vcp1 = vc_.points[0];
  const VelocityPoint& vcp2 = vc_.points[1];
  const float rn1_a = cross(vcp1.r_a, vc_.normal);
  const float rn1_b = cross(vcp1.r_b, vc_.normal);
  const float rn2_a = cross(vcp2.r_a, vc_.normal);
  const float rn2_b = cross(vcp2.r_b, vc_.normal);
  const float k11 = m_a + m_b + i_a * rn1_a * rn1_a + i_b * rn1_b * rn1_b;
  const float k22 = m_a + m_b + i_a * rn2_a * rn2_a + i_b * rn2_b * rn2_b;
  const float k12 = m_a + m_b + i_a * rn1_a * rn2_a + i_b * rn1_b * rn2_b;
  const float k_max_condition_number = 1000.0f;
  if (k11 * k11 < k_max_condition_number * (k11 * k22 - k12 * k12)) {
    vc_.K.ex = {k11, k12};
    vc_.K.ey = {k12, k22};
    vc_.normal_mass = inverse(vc_.K);
  } else {
    vc_.point_count = 1;
  }
}

// b2_contact_solver.cpp, b2ContactSolver::WarmStart: apply the carried impulses P = pn n + pt t.
void ContactSolver::warm_start() {
  if (contact_ == nullptr) return;
  PairVelocity u = load();
  const Vec2 normal = vc_.normal;
  const Vec2 tangent = cross(normal, 1.0f);
  for (int j = 0; j < vc_.point_count; ++j) {
    const VelocityPoint& vcp = vc_.points[j];
    const Vec2 P = vcp.normal_impulse * normal + vcp.tangent_impulse * tangent;
    u.w_a -= vc_.inv_i_a * cross(vcp.r_a, P);
    u.v_a -= vc_.inv_mass_a * P;
    u.w_b += vc_.inv_i_b * cross(vcp.r_b, P);
    u.v_b += vc_.inv_mass_b * P;
  }
  save(u);
}

// b2_contact_solver.cpp, b2ContactSolver::SolveVelocityConstraints: friction first, then the
// normal impulses (one point alone, two as a block).
void ContactSolver::solve_velocity_constraints() {
  if (contact_ == nullptr) return;
  PairVelocity u = load();
  solve_friction(u);
  if (vc_.point_count == 1) {
    solve_normal_points(u);
  } else {
    solve_normal_block(u);
  }
  save(u);
}

// b2_contact_solver.cpp, SolveVelocityConstraints, tangent part: per point the impulse that stops
// the tangential slip, with the accumulated impulse clamped to +-friction x its normal impulse.
void ContactSolver::solve_friction(PairVelocity& u) {
  const Vec2 tangent = cross(vc_.normal, 1.0f);
  for (int j = 0; j < vc_.point_count; ++j) {
    VelocityPoint& vcp = vc_.points[j];
    const Vec2 dv = relative_velocity(u, vcp);
    const float vt = dot(dv, tangent) - vc_.tangent_speed;
    float lambda = vcp.tangent_mass * (-vt);
    const float max_friction = vc_.friction * vcp.normal_impulse;
    const float new_impulse = clamp(vcp.tangent_impulse + lambda, -max_friction, max_friction);
    lambda = new_impulse - vcp.tangent_impulse;
    vcp.tangent_impulse = new_impulse;
    const Vec2 P = lambda * tangent;
    u.v_a -= vc_.inv_mass_a * P;
    u.w_a -= vc_.inv_i_a * cross(vcp.r_a, P);
    u.v_b += vc_.inv_mass_b * P;
    u.w_b += vc_.inv_i_b * cross(vcp.r_b, P);
  }
}

// b2_contact_solver.cpp, SolveVelocityConstraints, single-point normal part: the impulse that
// brings the normal velocity to the bias, the accumulated impulse kept >= 0.
void ContactSolver::solve_normal_points(PairVelocity& u) {
  for (int j = 0; j < vc_.point_count; ++j) {
    VelocityPoint& vcp = vc_.points[j];
    const Vec2 dv = relative_velocity(u, vcp);
    const float vn = dot(dv, vc_.normal);
    float lambda = -vcp.normal_mass * (vn - vcp.velocity_bias);
    const float new_impulse = max_f(vcp.normal_impulse + lambda, 0.0f);
    lambda = new_impulse - vcp.normal_impulse;
    vcp.normal_impulse = new_impulse;
    const Vec2 P = lambda * vc_.normal;
    u.v_a -= vc_.inv_mass_a * P;
    u.w_a -= vc_.inv_i_a * cross(vcp.r_a, P);
    u.v_b += vc_.inv_mass_b * P;
    u.w_b += vc_.inv_i_b * cross(vcp.r_b, P);
  }
}

// b2_contact_solver.cpp, SolveVelocityConstraints, block part: the 2-point LCP vn = K x + b',
// b' = vn0 - bias - K a (a: the accumulated impulses), solved by total enumeration: both points
// pushing (x = -K^-1 b'), only point 1, only point 2, none; the first admissible case is applied,
// none admissible leaves the impulses as they are.
void ContactSolver::solve_normal_block(PairVelocity& u) {
  VelocityPoint& cp1 = vc_.points[0];
  VelocityPoint& cp2 = vc_.points[1];
  const Vec2 a{cp1.normal_impulse, cp2.normal_impulse};
  const Vec2 dv1 = relative_velocity(u, cp1);
  const Vec2 dv2 = relative_velocity(u, cp2);
  float vn1 = dot(dv1, vc_.normal);
  float vn2 = dot(dv2, vc_.normal);
  Vec2 b;
  b.x = vn1 - cp1.velocity_bias;
  b.y = vn2 - cp2.velocity_bias;
  b -= mul(vc_.K, a);

  Vec2 x = -mul(vc_.normal_mass, b);  // case 1: vn1 = vn2 = 0
  if (x.x >= 0.0f && x.y >= 0.0f) return apply_block(u, x, a);

  x.x = -cp1.normal_mass * b.x;  // case 2: vn1 = 0, x2 = 0
  x.y = 0.0f;
  vn2 = vc_.K.ex.y * x.x + b.y;
  if (x.x >= 0.0f && vn2 >= 0.0f) return apply_block(u, x, a);

  x.x = 0.0f;  // case 3: x1 = 0, vn2 = 0
  x.y = -cp2.normal_mass * b.y;
  vn1 = vc_.K.ey.x * x.y + b.x;
  if (x.y >= 0.0f && vn1 >= 0.0f) return apply_block(u, x, a);

  x.x = 0.0f;  // case 4: x1 = x2 = 0
  x.y = 0.0f;
  vn1 = b.x;
  vn2 = b.y;
  if (vn1 >= 0.0f && vn2 >= 0.0f) return apply_block(u, x, a);
}

// b2_contact_solver.cpp, SolveVelocityConstraints, each block case's tail: apply the increments
// d = x - a at both points at once and accumulate x.
void ContactSolver::apply_block(PairVelocity& u, Vec2 x, Vec2 a) {
  VelocityPoint& cp1 = vc_.points[0];
  VelocityPoint& cp2 = vc_.points[1];
  const Vec2 d = x - a;
  const Vec2 P1 = d.x * vc_.normal;
  const Vec2 P2 = d.y * vc_.normal;
  u.v_a -= vc_.inv_mass_a * (P1 + P2);
  u.w_a -= vc_.inv_i_a * (cross(cp1.r_a, P1) + cross(cp2.r_a, P2));
  u.v_b += vc_.inv_mass_b * (P1 + P2);
  u.w_b += vc_.inv_i_b * (cross(cp1.r_b, P1) + cross(cp2.r_b, P2));
  cp1.normal_impulse = x.x;
  cp2.normal_impulse = x.y;
}

// b2_contact_solver.cpp, b2ContactSolver::StoreImpulses: the solved points' impulses back into
// the manifold for the next step's warm start.
void ContactSolver::store_impulses() {
  if (contact_ == nullptr) return;
  for (int j = 0; j < vc_.point_count; ++j) {
    contact_->manifold.points[j].normal_impulse = vc_.points[j].normal_impulse;
    contact_->manifold.points[j].tangent_impulse = vc_.points[j].tangent_impulse;
  }
}

// b2_contact_solver.cpp, b2PositionSolverManifold::Initialize: point `index`'s current normal
// (A to B), position (on the incident body; for circles midway between the centres) and
// separation beyond both skins (or radii).
struct PositionManifold {
  Vec2 normal, point;
  float separation = 0.0f;
};

PositionManifold position_manifold(const PositionConstraint& pc, const Xf& xf_a, const Xf& xf_b,
                                   int index) {
  PositionManifold out;
  if (pc.type == ManifoldType::circles) {
    const Vec2 point_a = mul(xf_a, pc.local_point);
    const Vec2 point_b = mul(xf_b, pc.local_points[0]);
    out.normal = point_b - point_a;
    normalize(out.normal);
    out.point = 0.5f * (point_a + point_b);
    out.separation = dot(point_b - point_a, out.normal) - pc.radius_a - pc.radius_b;
  } else if (pc.type == ManifoldType::face_a) {
    out.normal = mul(xf_a.q, pc.local_normal);
    const Vec2 plane_point = mul(xf_a, pc.local_point);
    const Vec2 clip_point = mul(xf_b, pc.local_points[index]);
    out.separation = dot(clip_point - plane_point, out.normal) - pc.radius_a - pc.radius_b;
    out.point = clip_point;
  } else {
    out.normal = mul(xf_b.q, pc.local_normal);
    const Vec2 plane_point = mul(xf_b, pc.local_point);
    const Vec2 clip_point = mul(xf_a, pc.local_points[index]);
    out.separation = dot(clip_point - plane_point, out.normal) - pc.radius_a - pc.radius_b;
    out.point = clip_point;
    out.normal = -out.normal;
  }
  return out;
}

// b2_contact_solver.cpp, b2ContactSolver::SolvePositionConstraints and
// SolveTOIPositionConstraints, shared loop: per point the pseudo-impulse -C/K with
// C = clamp(baumgarte (separation + slop), -max correction, 0), applied to the positions at once.
// Returns the smallest separation met.
float ContactSolver::solve_positions(float baumgarte, float m_a, float i_a, float m_b, float i_b) {
  float min_separation = 0.0f;
  Vec2 c_a = positions_[pc_.index_a].c;
  float a_a = positions_[pc_.index_a].a;
  Vec2 c_b = positions_[pc_.index_b].c;
  float a_b = positions_[pc_.index_b].a;
  for (int j = 0; j < pc_.point_count; ++j) {
    const Xf xf_a = frame_of({c_a, a_a}, pc_.local_center_a);
    const Xf xf_b = frame_of({c_b, a_b}, pc_.local_center_b);
    const PositionManifold psm = position_manifold(pc_, xf_a, xf_b, j);
    const Vec2 r_a = psm.point - c_a;
    const Vec2 r_b = psm.point - c_b;
    min_separation = min_f(min_separation, psm.separation);
    const float C = clamp(baumgarte * (psm.separation + kLinearSlop), -kMaxLinearCorrection, 0.0f);
    const float rn_a = cross(r_a, psm.normal);
    const float rn_b = cross(r_b, psm.normal);
    const float K = m_a + m_b + i_a * rn_a * rn_a + i_b * rn_b * rn_b;
    const float impulse = K > 0.0f ? -C / K : 0.0f;
    const Vec2 P = impulse * psm.normal;
    c_a -= m_a * P;
    a_a -= i_a * cross(r_a, P);
    c_b += m_b * P;
    a_b += i_b * cross(r_b, P);
  }
  positions_[pc_.index_a] = {c_a, a_a};
  positions_[pc_.index_b] = {c_b, a_b};
  return min_separation;
}

// b2_contact_solver.cpp, b2ContactSolver::SolvePositionConstraints: done when no point is deeper
// than 3 slops.
bool ContactSolver::solve_position_constraints() {
  if (contact_ == nullptr) return true;
  const float min_separation =
      solve_positions(kBaumgarte, pc_.inv_mass_a, pc_.inv_i_a, pc_.inv_mass_b, pc_.inv_i_b);
  return min_separation >= -3.0f * kLinearSlop;
}

// b2_contact_solver.cpp, b2ContactSolver::SolveTOIPositionConstraints: only the TOI bodies move
// (the others count as infinitely heavy); done within 1.5 slops.
bool ContactSolver::solve_toi_position_constraints(int toi_index_a, int toi_index_b) {
  if (contact_ == nullptr) return true;
  float m_a = 0.0f, i_a = 0.0f;
  if (pc_.index_a == toi_index_a || pc_.index_a == toi_index_b) {
    m_a = pc_.inv_mass_a;
    i_a = pc_.inv_i_a;
  }
  float m_b = 0.0f, i_b = 0.0f;
  if (pc_.index_b == toi_index_a || pc_.index_b == toi_index_b) {
    m_b = pc_.inv_mass_b;
    i_b = pc_.inv_i_b;
  }
  const float min_separation = solve_positions(kToiBaumgarte, m_a, i_a, m_b, i_b);
  return min_separation >= -1.5f * kLinearSlop;
}

// ---------------------------------------------------------------------------------------------
// b2_island.cpp: the island of the dynamic body, the static one and their touching contact.

struct Island {
  Body* bodies[2] = {nullptr, nullptr};
  int body_count = 0;
  Contact* contact = nullptr;
  Position positions[2];
  Velocity velocities[2];

  // b2_island.h, b2Island::Add(b2Body*)
  void add(Body& b) {
    b.island_index = body_count;
    bodies[body_count++] = &b;
  }
};

// b2_island.cpp, b2Island::Solve, first loop: the sweep's start at the current state; a dynamic
// body's velocity gains h/m (m g + F) and is damped by the Pade factor 1/(1 + h c).
void integrate_velocity(Body& b, float h, Vec2 gravity, Position& p, Velocity& u) {
  const Vec2 c = b.sweep.c;
  const float a = b.sweep.a;
  Vec2 v = b.v;
  float w = b.w;
  b.sweep.c0 = b.sweep.c;
  b.sweep.a0 = b.sweep.a;
  if (!b.is_static) {
    v += h * b.inv_mass * (b.gravity_scale * b.mass * gravity + b.force);
    w += h * b.inv_I * b.torque;
    v *= 1.0f / (1.0f + h * b.linear_damping);
    w *= 1.0f / (1.0f + h * b.angular_damping);
  }
  p = {c, a};
  u = {v, w};
}

// b2_island.cpp, b2Island::Solve / SolveTOI, position integration: the velocity scaled down to at
// most b2_maxTranslation and b2_maxRotation per step, then c += h v, a += h w.
void integrate_position(float h, Position& p, Velocity& u) {
  Vec2 c = p.c;
  float a = p.a;
  Vec2 v = u.v;
  float w = u.w;
  const Vec2 translation = h * v;
  if (dot(translation, translation) > kMaxTranslationSquared) {
    const float ratio = kMaxTranslation / length(translation);
    v *= ratio;
  }
  const float rotation = h * w;
  if (rotation * rotation > kMaxRotationSquared) {
    const float ratio = kMaxRotation / abs_f(rotation);
    w *= ratio;
  }
  c += h * v;
  a += h * w;
  p = {c, a};
  u = {v, w};
}

// b2_island.cpp, b2Island::Solve (no joints, no listener, sleeping off): velocities, the contact
// solver's warm start and velocity iterations, positions, position iterations with early exit,
// and the result written back to the bodies.
void solve_island(Island& island, const Body& body_a, const Body& body_b, const TimeStep& step,
                  Vec2 gravity) {
  const float h = step.dt;
  for (int i = 0; i < island.body_count; ++i) {
    integrate_velocity(*island.bodies[i], h, gravity, island.positions[i], island.velocities[i]);
  }
  ContactSolver solver(step, island.contact, body_a, body_b, island.positions, island.velocities);
  solver.initialize_velocity_constraints();
  if (step.warm_starting) solver.warm_start();
  for (int i = 0; i < step.velocity_iterations; ++i) solver.solve_velocity_constraints();
  solver.store_impulses();
  for (int i = 0; i < island.body_count; ++i) {
    integrate_position(h, island.positions[i], island.velocities[i]);
  }
  for (int i = 0; i < step.position_iterations; ++i) {
    if (solver.solve_position_constraints()) break;
  }
  for (int i = 0; i < island.body_count; ++i) {
    Body& b = *island.bodies[i];
    b.sweep.c = island.positions[i].c;
    b.sweep.a = island.positions[i].a;
    b.v = island.velocities[i].v;
    b.w = island.velocities[i].w;
    synchronize_transform(b);
  }
}

// b2_island.cpp, b2Island::SolveTOI: push the TOI bodies apart (TOI position iterations), take that
// as the sweeps' new start, solve the contact's velocities without warm start and integrate the
// rest of the step; the impulses are not stored.
void solve_island_toi(Island& island, const Body& body_a, const Body& body_b,
                      const TimeStep& sub_step, int toi_index_a, int toi_index_b) {
  for (int i = 0; i < island.body_count; ++i) {
    const Body& b = *island.bodies[i];
    island.positions[i] = {b.sweep.c, b.sweep.a};
    island.velocities[i] = {b.v, b.w};
  }
  ContactSolver solver(sub_step, island.contact, body_a, body_b, island.positions,
                       island.velocities);
  for (int i = 0; i < sub_step.position_iterations; ++i) {
    if (solver.solve_toi_position_constraints(toi_index_a, toi_index_b)) break;
  }
  Body& ba = *island.bodies[toi_index_a];
  Body& bb = *island.bodies[toi_index_b];
  ba.sweep.c0 = island.positions[toi_index_a].c;
  ba.sweep.a0 = island.positions[toi_index_a].a;
  bb.sweep.c0 = island.positions[toi_index_b].c;
  bb.sweep.a0 = island.positions[toi_index_b].a;
  solver.initialize_velocity_constraints();
  for (int i = 0; i < sub_step.velocity_iterations; ++i) solver.solve_velocity_constraints();
  const float h = sub_step.dt;
  for (int i = 0; i < island.body_count; ++i) {
    integrate_position(h, island.positions[i], island.velocities[i]);
    Body& b = *island.bodies[i];
    b.sweep.c = island.positions[i].c;
    b.sweep.a = island.positions[i].a;
    b.v = island.velocities[i].v;
    b.w = island.velocities[i].w;
    synchronize_transform(b);
  }
}

// ---------------------------------------------------------------------------------------------
// b2_world.cpp and b2_contact_manager.cpp: the world and its step.

struct World {
  Vec2 gravity;
  Body bodies[2];   // creation order: body i's fixture has proxy id i
  int index_a = 0;  // the body of the contact's fixture A (b2Contact::Create)
  std::optional<Contact> contact;
  float inv_dt0 = 0.0f;
  bool step_complete = true;
  bool new_contacts = false;

  Body& dynamic_body() { return bodies[0].is_static ? bodies[1] : bodies[0]; }
  Body& static_body() { return bodies[0].is_static ? bodies[0] : bodies[1]; }
  Body& body_a() { return bodies[index_a]; }
  Body& body_b() { return bodies[1 - index_a]; }
};

// b2_contact.cpp, b2Contact::Create with b2Contact::AddType's registers: the broad-phase pair
// comes as (lower proxy id, higher), body 0's fixture first; the register of (circle, polygon) is
// not primary and swaps the fixtures, so that a polygon and a circle make the polygon fixture A
// (b2PolygonAndCircleContact); two polygons or two circles keep the pair's order.
int fixture_a_body(const Body bodies[2]) {
  const bool swap = bodies[0].shape.is_circle && !bodies[1].shape.is_circle;
  return swap ? 1 : 0;
}

// b2_broad_phase.h, b2BroadPhase::UpdatePairs with b2_contact_manager.cpp,
// b2ContactManager::AddPair: each proxy in the move buffer queries the tree with its fat AABB;
// with two proxies the one pair is reported when either moved and the fat AABBs overlap, and
// AddPair creates the contact unless it exists (a dynamic and a static body always collide).
void find_new_contacts(World& w) {
  const bool moved = w.bodies[0].moved || w.bodies[1].moved;
  if (moved && !w.contact && test_overlap(w.bodies[0].fat, w.bodies[1].fat)) {
    w.contact = make_contact(w.body_a(), w.body_b());
  }
  w.bodies[0].moved = false;
  w.bodies[1].moved = false;
}

// b2_contact_manager.cpp, b2ContactManager::Collide: a contact whose fat AABBs no longer overlap
// is destroyed, else its manifold is updated (the dynamic body is always awake).
void collide(World& w) {
  if (!w.contact) return;
  if (!test_overlap(w.body_a().fat, w.body_b().fat)) {
    w.contact.reset();
    return;
  }
  update_contact(*w.contact, w.body_a(), w.body_b());
}

// b2_world.cpp, b2World::Solve: the island grown from the dynamic body over its touching contact
// (dynamic body first, the static one second), solved; then the dynamic body's proxy follows and
// new pairs are looked for.
void world_solve(World& w, const TimeStep& step) {
  for (Body& b : w.bodies) b.island = false;
  if (w.contact) w.contact->island = false;
  Island island;
  Body& seed = w.dynamic_body();
  island.add(seed);
  seed.island = true;
  seed.awake = true;
  Contact* c = w.contact ? &*w.contact : nullptr;
  if (c != nullptr && !c->island && c->enabled && c->touching) {
    island.contact = c;
    c->island = true;
    Body& other = w.static_body();
    if (!other.island) {
      other.island = true;
      island.add(other);  // popped from the search stack next; a static body ends the search
    }
  }
  solve_island(island, w.body_a(), w.body_b(), step, w.gravity);
  w.static_body().island = false;
  for (Body& b : w.bodies) {
    if (b.island && !b.is_static) synchronize_fixtures(b);
  }
  find_new_contacts(w);
}

// b2_world.cpp, b2World::SolveTOI, the search for one contact's TOI: both sweeps brought to the
// later start alpha0, b2TimeOfImpact over the rest of the step, alpha = its time mapped back onto
// the step (1 when not touching), cached on the contact.
float contact_toi(World& w, Contact& c) {
  Body& ba = w.body_a();
  Body& bb = w.body_b();
  // activeA || activeB and collideA || collideB: the dynamic body is awake, the other static.
  float alpha0 = ba.sweep.alpha0;
  if (ba.sweep.alpha0 < bb.sweep.alpha0) {
    alpha0 = bb.sweep.alpha0;
    ba.sweep.advance(alpha0);
  } else if (bb.sweep.alpha0 < ba.sweep.alpha0) {
    alpha0 = ba.sweep.alpha0;
    bb.sweep.advance(alpha0);
  }
  const ToiOutput output =
      time_of_impact(proxy_of(ba.shape), proxy_of(bb.shape), ba.sweep, bb.sweep, 1.0f);
  const float beta = output.t;
  float alpha = 1.0f;
  if (output.state == ToiState::touching) alpha = min_f(alpha0 + (1.0f - alpha0) * beta, 1.0f);
  c.toi = alpha;
  c.toi_flag = true;
  return alpha;
}

// b2_world.cpp, b2World::SolveTOI, one event: advance both bodies to the TOI; if the updated
// contact touches, solve the TOI island (the two bodies; no other contact exists) over the rest of
// the step and resynchronize the proxy, else restore the sweeps and disable the contact for the
// rest of this step.
void solve_toi_event(World& w, Contact& c, float min_alpha, const TimeStep& step) {
  Body& ba = w.body_a();
  Body& bb = w.body_b();
  const Sweep backup1 = ba.sweep;
  const Sweep backup2 = bb.sweep;
  advance_body(ba, min_alpha);
  advance_body(bb, min_alpha);
  update_contact(c, ba, bb);
  c.toi_flag = false;
  ++c.toi_count;
  if (!c.enabled || !c.touching) {
    c.enabled = false;
    ba.sweep = backup1;
    bb.sweep = backup2;
    synchronize_transform(ba);
    synchronize_transform(bb);
    return;
  }
  if (!ba.is_static) ba.awake = true;
  if (!bb.is_static) bb.awake = true;
  Island island;
  island.add(ba);
  island.add(bb);
  island.contact = &c;
  ba.island = true;
  bb.island = true;
  c.island = true;
  TimeStep sub_step;
  sub_step.dt = (1.0f - min_alpha) * step.dt;
  sub_step.inv_dt = 1.0f / sub_step.dt;
  sub_step.dt_ratio = 1.0f;
  sub_step.position_iterations = 20;
  sub_step.velocity_iterations = step.velocity_iterations;
  sub_step.warm_starting = false;
  solve_island_toi(island, ba, bb, sub_step, ba.island_index, bb.island_index);
  for (int i = 0; i < island.body_count; ++i) {
    Body& b = *island.bodies[i];
    b.island = false;
    if (b.is_static) continue;
    synchronize_fixtures(b);
    c.toi_flag = false;
    c.island = false;
  }
  find_new_contacts(w);
}

// b2_world.cpp, b2World::SolveTOI: after a complete step every sweep restarts at 0 and every TOI
// is stale; then repeatedly the earliest TOI below 1 - 10 eps is handled (a contact at most
// b2_maxSubSteps + 1 times), until none is left.
void world_solve_toi(World& w, const TimeStep& step) {
  if (w.step_complete) {
    for (Body& b : w.bodies) {
      b.island = false;
      b.sweep.alpha0 = 0.0f;
    }
    if (w.contact) {
      w.contact->toi_flag = false;
      w.contact->island = false;
      w.contact->toi_count = 0;
      w.contact->toi = 1.0f;
    }
  }
  for (;;) {
    Contact* min_contact = nullptr;
    float min_alpha = 1.0f;
    Contact* c = w.contact ? &*w.contact : nullptr;
    if (c != nullptr && c->enabled && c->toi_count <= kMaxSubSteps) {
      const float alpha = c->toi_flag ? c->toi : contact_toi(w, *c);
      if (alpha < min_alpha) {
        min_contact = c;
        min_alpha = alpha;
      }
    }
    if (min_contact == nullptr || 1.0f - 10.0f * kEpsilon < min_alpha) {
      w.step_complete = true;
      break;
    }
    solve_toi_event(w, *min_contact, min_alpha, step);
    // A contact made by find_new_contacts is the same optional: re-read it on the next pass.
  }
}

// b2_world.cpp, b2World::Step: new pairs (first step), the step's constants (dtRatio = dt/dt0,
// 0 on the first step), Collide, Solve, SolveTOI, then the forces cleared.
void world_step(World& w, float dt, int velocity_iterations, int position_iterations) {
  if (w.new_contacts) {
    find_new_contacts(w);
    w.new_contacts = false;
  }
  TimeStep step;
  step.dt = dt;
  step.velocity_iterations = velocity_iterations;
  step.position_iterations = position_iterations;
  step.inv_dt = dt > 0.0f ? 1.0f / dt : 0.0f;
  step.dt_ratio = w.inv_dt0 * dt;
  step.warm_starting = true;
  collide(w);
  if (w.step_complete && step.dt > 0.0f) world_solve(w, step);
  if (step.dt > 0.0f) world_solve_toi(w, step);
  if (step.dt > 0.0f) w.inv_dt0 = step.inv_dt;
  for (Body& b : w.bodies) {  // b2World::ClearForces
    b.force = {0.0f, 0.0f};
    b.torque = 0.0f;
  }
}

// ---------------------------------------------------------------------------------------------
// The replay's own frame: checks, creation, read-out.

bool finite(float v) {
  return std::isfinite(v);
}

void check_scope(std::span<const Box2dBox> bodies, float gx, float gy, float h,
                 const Box2dSolver& solver, std::int64_t steps) {
  auto fail = [](const char* why) {
    throw std::invalid_argument(std::string("box2d_replay: ") + why);
  };
  if (bodies.size() != 2) fail("needs exactly two bodies");
  if (bodies[0].is_static == bodies[1].is_static) fail("needs one dynamic and one static body");
  for (const Box2dBox& b : bodies) {
    for (float v : {b.radius, b.x, b.y, b.angle, b.vx, b.vy, b.w, b.density, b.friction,
                    b.restitution, b.linear_damping, b.angular_damping}) {
      if (!finite(v)) fail("a body parameter is not finite");
    }
    if (b.radius < 0.0f) fail("a negative radius");
    if (b.radius == 0.0f) {  // a box: its half extents
      if (!finite(b.hx) || !finite(b.hy)) fail("a body parameter is not finite");
      if (!(b.hx > 0.0f && b.hy > 0.0f)) fail("a half extent is not positive");
    }
    if (!b.is_static && !(b.density > 0.0f)) fail("the dynamic body needs a positive density");
    if (b.friction < 0.0f || b.restitution < 0.0f) fail("negative friction or restitution");
    if (b.linear_damping < 0.0f || b.angular_damping < 0.0f) fail("negative damping");
  }
  if (!finite(gx) || !finite(gy)) fail("gravity is not finite");
  if (!finite(h) || !(h > 0.0f)) fail("h must be positive and finite");
  if (solver.velocity_iterations < 0 || solver.position_iterations < 0) {
    fail("negative iteration count");
  }
  if (steps < 0) fail("negative step count");
}

// b2_world.cpp, b2World::CreateBody and b2_body.cpp, b2Body::CreateFixture, in the given order.
World create_world(std::span<const Box2dBox> bodies, float gx, float gy) {
  World w;
  w.gravity = {gx, gy};
  for (int i = 0; i < 2; ++i) {
    w.bodies[i] = create_body(bodies[static_cast<std::size_t>(i)]);
    create_fixture(w.bodies[i], bodies[static_cast<std::size_t>(i)]);
  }
  w.index_a = fixture_a_body(w.bodies);
  w.new_contacts = true;
  return w;
}

Box2dState state_of(const Body& b) {
  return {b.xf.p.x, b.xf.p.y, b.sweep.a, b.v.x, b.v.y, b.w};
}

}  // namespace box2d
}  // namespace

std::vector<Box2dState> box2d_replay(std::span<const Box2dBox> bodies, float gx, float gy, float h,
                                     const Box2dSolver& solver, std::int64_t steps) {
  box2d::check_scope(bodies, gx, gy, h, solver, steps);
  box2d::World w = box2d::create_world(bodies, gx, gy);
  std::vector<Box2dState> out;
  out.reserve(static_cast<std::size_t>(steps + 1) * 2);
  for (std::int64_t n = 0;; ++n) {
    out.push_back(box2d::state_of(w.bodies[0]));
    out.push_back(box2d::state_of(w.bodies[1]));
    if (n == steps) break;
    box2d::world_step(w, h, solver.velocity_iterations, solver.position_iterations);
  }
  return out;
}

}  // namespace dropcheck
