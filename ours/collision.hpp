// The part the seed announces after Part III: collision detection and resolution, with mass and
// friction. The seed's cubes fall through its static floor cube; with World::collisions on they
// land on it, slide on it with Coulomb friction, bounce with a restitution, and rest on each other.
//
// Per fixed step h (ApplyPhysics, physics.hpp), with collisions on:
//   FindContacts         every pair that touches or overlaps where the last step left it:
//                        the normal n (out of the lower body), the depth d >= 0, and the
//                        approach speed a = -(v_body - v_other).n at the step's start
//   ApplyGravity, IntegrateLinearVelocity    v_free = f*(v + (g + F/m)*h)       (Part III's order)
//   ResolveContacts      bottom up, each body against the one under it taken as immovable:
//                          target = e*a when a > 0, else 0                (restitution)
//                          j_n    = max(target - v_rel.n, 0)             (the contact only pushes)
//                          v     += j_n*n
//                          v_t    = tangential v_rel; |v_t| <= mu*j_n ? v_t = 0
//                                                                 : v_t -= mu*j_n*v_t/|v_t|
//   IntegratePosition    x += h*v, then x += d*n                         (the depth pushed out)
//   IntegrateAngularForce                                                (Part III's)
//
// This is dropcheck's ideal contact law with a full push-out in position: friction is a velocity
// clamp on a cone (|f_t| <= mu*f_n) before the position update, restitution acts on the approach
// speed the step started with, and no energy is added by the push (it moves, it does not speed).
// Resolving from the floor up (each body's support already final) holds a resting stack exactly.
// The contact impulse acts through the centre of mass: a box slides and lands flat, a sphere
// slides without rolling. Scope: boxes that are not turned (axis-aligned) and spheres; the adapter
// refuses a contact scene with a turned or turning box.
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
  T approach = T(0);                        // m/s: -(v_body - v_other).n at the step's start
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

// The contact of a against b, its normal from b to a; false when they are apart.
template <typename T, typename Model>
bool Touch(const Model& a, const Model& b, Vector3<T>& normal, T& depth) {
  const Collider<T>& ca = a.collider;
  const Collider<T>& cb = b.collider;
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
  return BoxBoxContact(a.translation, ca.halfExtents, b.translation, cb.halfExtents, normal, depth);
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
      if (!Touch<T>(a, b, c.normal, c.depth)) continue;
      // The upper body (along gravity's opposite, which the normal follows on a floor) is `body`;
      // a static body is never it.
      const bool aUp = !a.rigidBody.isStatic && (b.rigidBody.isStatic || c.normal.y() >= T(0));
      c.body = aUp ? i : j;
      c.other = aUp ? j : i;
      if (!aUp) c.normal = -c.normal;
      const Vector3<T> relative =
          models[c.body].rigidBody.velocity - models[c.other].rigidBody.velocity;
      c.approach = -relative.dot(c.normal);
      contacts.push_back(c);
    }
  return contacts;
}

// One contact's impulse, the lower body taken as immovable (its velocity already final).
template <typename T, typename Model>
void ResolveContact(std::span<Model> models, const Contact<T>& c, T friction, T restitution) {
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
