// The seed's physics.odin (Part III): RigidBody, ApplyPhysics, ApplyGravity, IntegrateLinearForce.
//
// Per fixed step h, for every body that is not static (semi-implicit / symplectic Euler):
//   v += g*h            ApplyGravity
//   v += (F/m)*h        IntegrateLinearForce (the seed has no mass; m defaults to 1)
//   F  = 0
//   v *= f              LINEAR_DRAG, a per-step factor
//   x += v*h
// Drag sits after gravity and force and before the position update: v_{n+1} = f*(v_n + a*h).
//
// Departures from the seed, all with the seed's values as defaults: `mass` on RigidBody, and the
// gravity and per-step drag as World settings so the harness can run at any h with f = exp(-k*h).
#pragma once

#include <span>

#include "constants.hpp"

namespace ours {

template <typename T>
struct RigidBody {
  Vector3<T> force = Vector3<T>::Zero();     // accumulator, cleared every step (N)
  Vector3<T> velocity = Vector3<T>::Zero();  // m/s
  bool isStatic = false;
  T mass = T(1);  // kg; the seed assumes 1
};

// The seed's Model keeps mesh, texture and rotation too; physics reads only these two members.
template <typename T>
struct Model {
  Vector3<T> translation = Vector3<T>::Zero();  // m
  RigidBody<T> rigidBody;
};

// World settings the seed hard-codes as constants.
template <typename T>
struct World {
  Vector3<T> gravity = GRAVITY<T>;
  T linearDrag = LINEAR_DRAG<T>;  // per-step factor in (0, 1]
};

// v += g*h
template <typename T>
void ApplyGravity(Model<T>* model, const World<T>& world, T deltaTime) {
  model->rigidBody.velocity += world.gravity * deltaTime;
}

// v += (F/m)*h; F = 0; v *= f; x += v*h
template <typename T>
void IntegrateLinearForce(Model<T>* model, const World<T>& world, T deltaTime) {
  RigidBody<T>& body = model->rigidBody;
  body.velocity += (body.force / body.mass) * deltaTime;
  body.force = Vector3<T>::Zero();
  body.velocity *= world.linearDrag;
  model->translation += body.velocity * deltaTime;
}

// One fixed step for every model that is not static.
template <typename T>
void ApplyPhysics(std::span<Model<T>> models, const World<T>& world, T deltaTime) {
  for (Model<T>& model : models) {
    if (model.rigidBody.isStatic) continue;
    ApplyGravity(&model, world, deltaTime);
    IntegrateLinearForce(&model, world, deltaTime);
  }
}

}  // namespace ours
