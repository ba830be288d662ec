// The seed's physics.odin (Part III): RigidBody, ApplyPhysics, ApplyGravity, IntegrateLinearForce,
// and the angular motion the seed announces next (torque, angularVelocity, ANGULAR_DRAG):
// IntegrateAngularForce.
//
// Per fixed step h, for every body that is not static (semi-implicit / symplectic Euler):
//   v += g*h            ApplyGravity
//   v += (F/m)*h        IntegrateLinearForce (the seed has no mass; m defaults to 1)
//   F  = 0
//   v *= f              LINEAR_DRAG, a per-step factor
//   x += v*h
// Drag sits after gravity and force and before the position update: v_{n+1} = f*(v_n + a*h).
//
// Then, per body, the angular motion (IntegrateAngularForce, after the linear update, which it
// never reads or changes), with R the rotation of q and I the principal moments in the body frame:
//   I_w = R*diag(I)*R^T                      inertia in the world frame
//   w += I_w^-1*(tau - w x (I_w*w))*h         Euler's equations, gyroscopic term at the step start
//   tau = 0
//   w *= f_a                                  ANGULAR_DRAG, a per-step factor
//   q = normalize(q + (h/2)*(0, w)*q)          first-order quaternion update with the new w
// Like the linear part: explicit forces (here the gyroscopic torque), drag after them, and the
// pose moved with the new velocity.
//
// Departures from the seed, all with the seed's values as defaults: `mass` and `inertia` on
// RigidBody, the gravity and per-step drags as World settings so the harness can run at any h with
// f = exp(-k*h), and the orientation as a quaternion `rotation` (the seed's Model keeps a
// rotationMatrix for drawing, which is R of this quaternion).
//
// Collisions (collision.hpp, the part the seed announces next) run only when World::collisions is
// on: Part III's step, as above, is then split around ResolveContacts, its arithmetic unchanged.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "collision.hpp"
#include "constants.hpp"

namespace ours {

template <typename T>
struct RigidBody {
  Vector3<T> force = Vector3<T>::Zero();     // accumulator, cleared every step (N)
  Vector3<T> velocity = Vector3<T>::Zero();  // m/s
  bool isStatic = false;
  T mass = T(1);                                    // kg; the seed assumes 1
  Vector3<T> torque = Vector3<T>::Zero();           // accumulator, cleared every step (N m, world)
  Vector3<T> angularVelocity = Vector3<T>::Zero();  // rad/s, world frame
  Vector3<T> inertia = Vector3<T>::Constant(T(1) / T(6));  // principal moments (kg m^2), body
                                                           // frame; default: the unit cube of 1 kg
};

// The seed's Model keeps mesh, texture and scale too; physics reads only these members.
template <typename T>
struct Model {
  Vector3<T> translation = Vector3<T>::Zero();         // m
  Quaternion<T> rotation = Quaternion<T>::Identity();  // body frame to world frame
  RigidBody<T> rigidBody;
  Collider<T> collider;  // what it collides as (collision.hpp)
};

// World settings the seed hard-codes as constants.
template <typename T>
struct World {
  Vector3<T> gravity = GRAVITY<T>;
  T linearDrag = LINEAR_DRAG<T>;    // per-step factor in (0, 1]
  T angularDrag = ANGULAR_DRAG<T>;  // per-step factor in (0, 1]
  bool collisions = false;          // Part III: off, the cubes fall through the floor
  T friction = T(0);                // Coulomb mu of every contact
  T restitution = T(0);             // e of every contact
};

// v += g*h
template <typename T>
void ApplyGravity(Model<T>* model, const World<T>& world, T deltaTime) {
  model->rigidBody.velocity += world.gravity * deltaTime;
}

// v += (F/m)*h; F = 0; v *= f
template <typename T>
void IntegrateLinearVelocity(Model<T>* model, const World<T>& world, T deltaTime) {
  RigidBody<T>& body = model->rigidBody;
  body.velocity += (body.force / body.mass) * deltaTime;
  body.force = Vector3<T>::Zero();
  body.velocity *= world.linearDrag;
}

// x += v*h
template <typename T>
void IntegratePosition(Model<T>* model, T deltaTime) {
  model->translation += model->rigidBody.velocity * deltaTime;
}

// v += (F/m)*h; F = 0; v *= f; x += v*h
template <typename T>
void IntegrateLinearForce(Model<T>* model, const World<T>& world, T deltaTime) {
  IntegrateLinearVelocity(model, world, deltaTime);
  IntegratePosition(model, deltaTime);
}

// Whether a body turns this step: it spins, or a torque twists it. A body that does neither keeps
// its rotation exactly (no renormalisation).
template <typename T>
bool Turns(const Model<T>& model) {
  return !model.rigidBody.angularVelocity.isZero(T(0)) || !model.rigidBody.torque.isZero(T(0));
}

// w += I_w^-1*(tau - w x (I_w*w))*h; tau = 0; w *= f_a
template <typename T>
void IntegrateAngularVelocity(Model<T>* model, const World<T>& world, T deltaTime) {
  RigidBody<T>& body = model->rigidBody;
  Vector3<T>& w = body.angularVelocity;
  const Matrix3<T> R = model->rotation.toRotationMatrix();
  // In the body frame I is diagonal: I_w*w = R*(I .* (R^T*w)), I_w^-1*t = R*((R^T*t) ./ I).
  const Vector3<T> momentum = R * body.inertia.cwiseProduct(R.transpose() * w);
  const Vector3<T> netTorque = body.torque - w.cross(momentum);
  w += R * (R.transpose() * netTorque).cwiseQuotient(body.inertia) * deltaTime;
  body.torque = Vector3<T>::Zero();
  w *= world.angularDrag;
}

// q = normalize(q + (h/2)*(0, w)*q)
template <typename T>
void IntegrateRotation(Model<T>* model, T deltaTime) {
  const Vector3<T>& w = model->rigidBody.angularVelocity;
  const Quaternion<T> spin(T(0), w.x(), w.y(), w.z());
  model->rotation.coeffs() += (spin * model->rotation).coeffs() * (deltaTime / T(2));
  model->rotation.normalize();
}

// w += I_w^-1*(tau - w x (I_w*w))*h; tau = 0; w *= f_a; q = normalize(q + (h/2)*(0, w)*q),
// for a body that turns.
template <typename T>
void IntegrateAngularForce(Model<T>* model, const World<T>& world, T deltaTime) {
  if (!Turns(*model)) return;
  IntegrateAngularVelocity(model, world, deltaTime);
  IntegrateRotation(model, deltaTime);
}

// One fixed step with collisions: contacts found where the last step left the bodies, the
// velocities (linear and angular) updated as in Part III, the contacts resolved, then the poses
// moved and the overlaps pushed out (collision.hpp). A body whose contact made it turn is turned
// by its new angular velocity in the same step.
template <typename T>
void ApplyPhysicsWithCollisions(std::span<Model<T>> models, const World<T>& world, T deltaTime) {
  std::vector<Contact<T>> contacts = FindContacts<T>(std::span<const Model<T>>(models));
  std::vector<char> turns(models.size(), 0);
  for (std::size_t i = 0; i < models.size(); ++i) {
    Model<T>& model = models[i];
    if (model.rigidBody.isStatic) continue;
    ApplyGravity(&model, world, deltaTime);
    IntegrateLinearVelocity(&model, world, deltaTime);
    turns[i] = Turns(model);
    if (turns[i]) IntegrateAngularVelocity(&model, world, deltaTime);
  }
  ResolveContacts(models, contacts, world.friction, world.restitution);
  for (std::size_t i = 0; i < models.size(); ++i) {
    Model<T>& model = models[i];
    if (model.rigidBody.isStatic) continue;
    IntegratePosition(&model, deltaTime);
    if (turns[i] || !model.rigidBody.angularVelocity.isZero(T(0)))
      IntegrateRotation(&model, deltaTime);
  }
  PushOut(models, contacts);
}

// One fixed step for every model that is not static.
template <typename T>
void ApplyPhysics(std::span<Model<T>> models, const World<T>& world, T deltaTime) {
  if (world.collisions) {
    ApplyPhysicsWithCollisions(models, world, deltaTime);
    return;
  }
  for (Model<T>& model : models) {
    if (model.rigidBody.isStatic) continue;
    ApplyGravity(&model, world, deltaTime);
    IntegrateLinearForce(&model, world, deltaTime);
    IntegrateAngularForce(&model, world, deltaTime);
  }
}

}  // namespace ours
