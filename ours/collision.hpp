// The part the seed announces after Part III: collision detection and resolution, with mass and
// friction. The seed's cubes fall through its static floor cube; with World::collisions on they
// land on it, slide on it with Coulomb friction, bounce with a restitution, rest on each other, and
// a turning cube lands on a corner or an edge and tumbles.
//
// Per fixed step h (ApplyPhysics, physics.hpp), with collisions on:
//   FindContacts         every pair that touches or overlaps where the last step left it:
//                        the normal n (out of the lower body), the depth d >= 0, the contact
//                        point, and the approach speed a = -(u_body - u_other).n at the step's
//                        start, u the velocity of the point the impulse acts at
//   ApplyGravity, IntegrateLinearVelocity, IntegrateAngularVelocity    (Part III's arithmetic)
//   ResolveContacts      bottom up, each body against the one under it taken as immovable:
//                          target = e*a when a > 0, else 0                (restitution)
//                          j_n    = max(target - u.n, 0)/(n.K n)          (the contact only pushes)
//                          u      = the point's velocity after j_n
//                          t      = the slip u - (u.n)n over its length |u_t|
//                          j_t    = min(|u_t|/(t.K t), mu*j_n)            (Coulomb: stop the slip
//                                                                          or slide on the cone)
//                        K d = d/m + I_w^-1*(r x d) x r: the point's velocity change per unit
//                        impulse along d, r the arm from the centre of mass to the point
//   IntegratePosition, IntegrateRotation    x += h*v, q turned by the new w; then x += d*n
//
// Where the impulse acts (r):
//   - a box that is neither turned nor turning, and a sphere: through its centre of mass (r = 0,
//     K = 1/m): a box slides and lands flat, its face holding it upright; a sphere slides without
//     rolling. Then j_t/m = min(|u_t|, mu*j_n/m): friction is a velocity clamp on the cone.
//   - a turned or turning box: at the mean of its corners that are in the lower box (at or below
//     its face), so that landing on a corner or an edge turns it.
// This is dropcheck's ideal contact law with a full push-out in position: friction acts before the
// position update, restitution acts on the approach speed the step started with, and no energy is
// added by the push (it moves, it does not speed). Resolving from the floor up (each body's support
// already final) holds a resting stack exactly. Scope: a turned or turning box collides with the
// unturned boxes below it (its corners against their faces; edge against edge is not seen).
#pragma once

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "constants.hpp"

namespace ours {

enum class Shape { Box, Sphere };

// What a body collides as (the seed's Model has a mesh; collision needs only its extent).
template <typename T>
struct Collider {
  Shape shape = Shape::Box;
  Vector3<T> halfExtents = Vector3<T>::Constant(T(0.5));  // m: the seed's unit cube
  T radius = T(0);                                        // m, a sphere's
};

// One touching or overlapping pair found at the step's start: `body` rests on or hits `other`.
template <typename T>
struct Contact {
  int body = 0;   // index of the upper body (never static)
  int other = 0;  // index of the body it touches, below it along the normal
  Vector3<T> normal = Vector3<T>::UnitY();  // unit, out of `other` towards `body`
  T depth = T(0);                           // m, >= 0: how far the two overlap
  T approach = T(0);                        // m/s: -(u_body - u_other).n at the step's start
  // The body is a turned or turning box: the impulse acts at `arm` from its centre of mass (the
  // mean of its corners in `other`), not through the centre.
  bool atPoint = false;
  Vector3<T> arm = Vector3<T>::Zero();  // m, world frame, at the step's start
};

// The overlap of two unturned boxes along each axis (>= 0 where they overlap or touch), and the
// contact along the axis of least overlap, its normal pointing from b to a.
template <typename T>
bool BoxBoxContact(const Vector3<T>& a, const Vector3<T>& ha, const Vector3<T>& b,
                   const Vector3<T>& hb, Vector3<T>& normal, T& depth) {
  int axis = -1;
  for (int i = 0; i < 3; ++i) {
    const T overlap = (ha[i] + hb[i]) - std::abs(a[i] - b[i]);
    if (overlap < T(0)) return false;  // apart along this axis
    if (axis < 0 || overlap < depth) {
      axis = i;
      depth = overlap;
    }
  }
  normal = Vector3<T>::Zero();
  normal[axis] = a[axis] >= b[axis] ? T(1) : T(-1);
  return true;
}

// A turned box (centre a, rotation q, half extents ha) against an unturned box below it: the normal
// along the lower box's axis of least overlap with the turned box's bounding box, and the turned
// box's corners at or below that face (within its extent on the two other axes). The depth is
// the deepest corner's, the point the mean of those corners.
template <typename T>
bool TurnedBoxContact(const Vector3<T>& a, const Quaternion<T>& q, const Vector3<T>& ha,
                      const Vector3<T>& b, const Vector3<T>& hb, Vector3<T>& normal, T& depth,
                      Vector3<T>& point) {
  const Matrix3<T> R = q.toRotationMatrix();
  const Vector3<T> reach = R.cwiseAbs() * ha;  // half extents of the bounding box
  if (!BoxBoxContact<T>(a, reach, b, hb, normal, depth)) return false;
  int axis = 0;
  for (int i = 1; i < 3; ++i)
    if (normal[i] != T(0)) axis = i;
  int touching = 0;
  depth = T(0);
  point = Vector3<T>::Zero();
  for (int k = 0; k < 8; ++k) {
    const Vector3<T> corner(k & 1 ? ha.x() : -ha.x(), k & 2 ? ha.y() : -ha.y(),
                            k & 4 ? ha.z() : -ha.z());
    const Vector3<T> p = a + R * corner;
    const Vector3<T> local = p - b;
    const T below = hb[axis] - normal[axis] * local[axis];  // >= 0: at or below the face
    bool inside = below >= T(0);
    for (int i = 0; i < 3; ++i)
      if (i != axis && std::abs(local[i]) > hb[i]) inside = false;
    if (!inside) continue;
    depth = std::max(depth, below);
    point += p;
    ++touching;
  }
  if (touching == 0) return false;
  point /= T(touching);
  return true;
}

// A sphere (centre c, radius r) against an unturned box: the closest point of the box to c.
template <typename T>
bool SphereBoxContact(const Vector3<T>& c, T r, const Vector3<T>& b, const Vector3<T>& hb,
                      Vector3<T>& normal, T& depth) {
  const Vector3<T> closest = (c - b).cwiseMax(-hb).cwiseMin(hb) + b;
  const Vector3<T> away = c - closest;
  const T distance = away.norm();
  if (distance > r) return false;
  if (distance == T(0))  // the centre inside the box: out along its box's least overlap
    return BoxBoxContact<T>(c, Vector3<T>::Constant(r), b, hb, normal, depth);
  normal = away / distance;
  depth = r - distance;
  return true;
}

// Two spheres: along the line between their centres.
template <typename T>
bool SphereSphereContact(const Vector3<T>& a, T ra, const Vector3<T>& b, T rb, Vector3<T>& normal,
                         T& depth) {
  const Vector3<T> away = a - b;
  const T distance = away.norm();
  if (distance > ra + rb || distance == T(0)) return false;
  normal = away / distance;
  depth = (ra + rb) - distance;
  return true;
}

// Whether a body is a box that is turned or turning: its contacts act at a point.
template <typename Model>
bool TurnedBox(const Model& m) {
  using T = typename decltype(m.translation)::Scalar;
  return m.collider.shape == Shape::Box &&
         (m.rotation.coeffs() != Quaternion<T>::Identity().coeffs() ||
          !m.rigidBody.angularVelocity.isZero(T(0)));
}

// The contact of a against b, its normal from b to a; false when they are apart. For a turned box
// (TurnedBox) `point` is where its contact acts, and `turned` says which of the two it is (1: a,
// 2: b, 0: neither).
template <typename T, typename Model>
bool Touch(const Model& a, const Model& b, Vector3<T>& normal, T& depth, Vector3<T>& point,
           int& turned) {
  const Collider<T>& ca = a.collider;
  const Collider<T>& cb = b.collider;
  turned = 0;
  if (ca.shape == Shape::Sphere && cb.shape == Shape::Sphere)
    return SphereSphereContact(a.translation, ca.radius, b.translation, cb.radius, normal, depth);
  if (ca.shape == Shape::Sphere)
    return SphereBoxContact(a.translation, ca.radius, b.translation, cb.halfExtents, normal, depth);
  if (cb.shape == Shape::Sphere) {
    if (!SphereBoxContact(b.translation, cb.radius, a.translation, ca.halfExtents, normal, depth))
      return false;
    normal = -normal;
    return true;
  }
  if (TurnedBox(a)) {
    turned = 1;
    return TurnedBoxContact(a.translation, a.rotation, ca.halfExtents, b.translation,
                            cb.halfExtents, normal, depth, point);
  }
  if (TurnedBox(b)) {
    turned = 2;
    if (!TurnedBoxContact(b.translation, b.rotation, cb.halfExtents, a.translation, ca.halfExtents,
                          normal, depth, point))
      return false;
    normal = -normal;
    return true;
  }
  return BoxBoxContact(a.translation, ca.halfExtents, b.translation, cb.halfExtents, normal, depth);
}

// The velocity of the point at `arm` from a body's centre of mass: v + w x r.
template <typename Model, typename V>
V PointVelocity(const Model& m, const V& arm) {
  return m.rigidBody.velocity + m.rigidBody.angularVelocity.cross(arm);
}

// Every touching pair, as (upper body, lower body): the body the normal points into is `body`. A
// static body is always the lower one; two static bodies are never a pair.
template <typename T, typename Model>
std::vector<Contact<T>> FindContacts(std::span<const Model> models) {
  std::vector<Contact<T>> contacts;
  const int n = static_cast<int>(models.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const Model &a = models[i], &b = models[j];
      if (a.rigidBody.isStatic && b.rigidBody.isStatic) continue;
      Contact<T> c;
      Vector3<T> point;
      int turned = 0;
      if (!Touch<T>(a, b, c.normal, c.depth, point, turned)) continue;
      // The upper body (along gravity's opposite, which the normal follows on a floor) is `body`;
      // a static body is never it.
      const bool aUp = !a.rigidBody.isStatic && (b.rigidBody.isStatic || c.normal.y() >= T(0));
      c.body = aUp ? i : j;
      c.other = aUp ? j : i;
      if (!aUp) c.normal = -c.normal;
      c.atPoint = turned == (aUp ? 1 : 2);
      if (c.atPoint) c.arm = point - models[c.body].translation;
      const Model& upper = models[c.body];
      const Vector3<T> relative =
          (c.atPoint ? PointVelocity(upper, c.arm) : upper.rigidBody.velocity) -
          models[c.other].rigidBody.velocity;
      c.approach = -relative.dot(c.normal);
      contacts.push_back(c);
    }
  return contacts;
}

// One contact of a turned box at its point (arm r): the impulses j_n along n, then j_t against the
// slip, each changing v by j/m and w by I_w^-1*(r x j) (the header's K).
template <typename T, typename Model>
void ResolvePointContact(std::span<Model> models, const Contact<T>& c, T friction, T restitution) {
  Model& m = models[c.body];
  auto& body = m.rigidBody;
  const Vector3<T>& support = models[c.other].rigidBody.velocity;
  const Matrix3<T> R = m.rotation.toRotationMatrix();
  const auto turnPer = [&](const Vector3<T>& j) {  // I_w^-1*(r x j)
    return Vector3<T>(R * (R.transpose() * c.arm.cross(j)).cwiseQuotient(body.inertia));
  };
  const auto response = [&](const Vector3<T>& d) {  // K d
    return Vector3<T>(d / body.mass + turnPer(d).cross(c.arm));
  };
  const auto apply = [&](const Vector3<T>& j) {
    body.velocity += j / body.mass;
    body.angularVelocity += turnPer(j);
  };
  const T target = c.approach > T(0) ? restitution * c.approach : T(0);
  const T normalSpeed = (PointVelocity(m, c.arm) - support).dot(c.normal);
  const T pushN = std::max(target - normalSpeed, T(0)) / c.normal.dot(response(c.normal));
  apply(pushN * c.normal);
  const Vector3<T> relative = PointVelocity(m, c.arm) - support;
  const Vector3<T> slip = relative - relative.dot(c.normal) * c.normal;
  const T slipSpeed = slip.norm();
  if (slipSpeed == T(0)) return;
  const Vector3<T> along = slip / slipSpeed;
  const T stop = slipSpeed / along.dot(response(along));
  apply(-std::min(stop, friction * pushN) * along);
}

// One contact's impulse, the lower body taken as immovable (its velocity already final).
template <typename T, typename Model>
void ResolveContact(std::span<Model> models, const Contact<T>& c, T friction, T restitution) {
  if (c.atPoint) {
    ResolvePointContact(models, c, friction, restitution);
    return;
  }
  Vector3<T>& v = models[c.body].rigidBody.velocity;
  const Vector3<T>& support = models[c.other].rigidBody.velocity;
  const T target = c.approach > T(0) ? restitution * c.approach : T(0);
  const T normalSpeed = (v - support).dot(c.normal);
  const T push = std::max(target - normalSpeed, T(0));  // per unit mass: j_n/m
  v += push * c.normal;
  const Vector3<T> relative = v - support;
  const Vector3<T> slip = relative - relative.dot(c.normal) * c.normal;
  const T slipSpeed = slip.norm();
  const T grip = friction * push;  // Coulomb: |j_t| <= mu*j_n
  if (slipSpeed <= grip)
    v -= slip;
  else
    v -= slip * (grip / slipSpeed);
}

// Contacts resolved from the bottom up: each in the order of its lower body's height, so that a
// body's support has its final velocity before the body is resolved against it.
template <typename T, typename Model>
void ResolveContacts(std::span<Model> models, std::vector<Contact<T>>& contacts, T friction,
                     T restitution) {
  std::stable_sort(contacts.begin(), contacts.end(), [&](const Contact<T>& a, const Contact<T>& b) {
    const bool sa = models[a.other].rigidBody.isStatic, sb = models[b.other].rigidBody.isStatic;
    if (sa != sb) return sa;
    return models[a.other].translation.y() < models[b.other].translation.y();
  });
  for (const Contact<T>& c : contacts) ResolveContact(models, c, friction, restitution);
}

// x += d*n for every contact: the overlap found at the step's start pushed out in position.
template <typename T, typename Model>
void PushOut(std::span<Model> models, const std::vector<Contact<T>>& contacts) {
  for (const Contact<T>& c : contacts) models[c.body].translation += c.depth * c.normal;
}

}  // namespace ours
