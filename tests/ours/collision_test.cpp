// Tests ours/collision.hpp through ApplyPhysics against the closed forms of its contact law
// (docs/contact.md): the clamp law's stop step and distance, the bounce's contact step and rebound,
// a stack held exactly, and Part III untouched when collisions are off.
//
// Slide, clamp law: each step takes mu*g*h off the speed, never more than is left, then x += h*v;
// the speed is 0 after N = ceil(v0/(mu*g*h)) steps, having travelled
//   h*((N - 1)*v0 - mu*g*h*(N - 1)*N/2).
// Bounce, from rest with the lowest point h0 above the floor: after n free steps the drop is
// g*h^2*n*(n + 1)/2; the contact step c is the first whose drop exceeds h0; the next step leaves
// at e*g*h*c (the step-start approach) and moves h*e*g*h*c plus the depth it started in.
// Edge landing: a unit cube of 1 kg (I = 1/6 about every axis) turned by theta about z lands on its
// lowest edge, whose midpoint sits at r = (r_x, r_y, 0) from its centre. Frictionless and with
// e = 0 one impulse j along y stops that point: K_nn = 1 + 6*r_x^2, j = -u_n/K_nn, so
//   v_y = u_n*6*r_x^2/(1 + 6*r_x^2),  w_z = 6*r_x*j = -6*r_x*u_n/(1 + 6*r_x^2)
// with u_n = v_y0 - g*h, the speed the step's gravity left.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "ours/physics.hpp"
#include "tests/ours/edge_landing.hpp"

namespace {

template <typename T>
ours::Model<T> floor_box() {
  ours::Model<T> m{};
  m.translation = {T(0), T(-0.5), T(0)};
  m.rigidBody.isStatic = true;
  m.collider.halfExtents = {T(10), T(0.5), T(10)};
  return m;
}

template <typename T>
ours::World<T> world(T friction, T restitution) {
  ours::World<T> w;
  w.linearDrag = T(1);
  w.angularDrag = T(1);
  w.collisions = true;
  w.friction = friction;
  w.restitution = restitution;
  return w;
}

}  // namespace

TEST_CASE("a cube slid at 5 m/s with mu 0.5 stops at the clamp law's step and distance",
          "[ours][collision]") {
  using T = double;
  const T h = T(1) / T(60), mu = 0.5, g = 9.8, v0 = 5.0;
  std::vector<ours::Model<T>> models(2);
  models[0] = floor_box<T>();
  models[1].translation = {0, 0.5, 0};
  models[1].rigidBody.velocity = {v0, 0, 0};
  const ours::World<T> w = world<T>(mu, 0);
  const int N = static_cast<int>(std::ceil(v0 / (mu * g * h)));
  REQUIRE(N == 62);
  int stop = -1;
  for (int n = 1; n <= 120; ++n) {
    ours::ApplyPhysics<T>(models, w, h);
    CHECK(models[1].translation.y() == 0.5);  // held at rest height from the first step
    if (stop < 0 && models[1].rigidBody.velocity.x() == 0.0) stop = n;
  }
  CHECK(stop == N);
  const double distance = h * ((N - 1) * v0 - mu * g * h * (N - 1) * N / 2);
  CHECK(distance == Approx(2.509472).margin(5e-7));
  CHECK(models[1].translation.x() == Approx(distance).margin(1e-12));
}

TEST_CASE("a slide at 45 degrees decelerates along its slip: the cone's figures",
          "[ours][collision]") {
  using T = double;
  const T h = T(1) / T(60), mu = 0.5, v0 = 5.0;
  std::vector<ours::Model<T>> models(2);
  models[0] = floor_box<T>();
  models[1].translation = {0, 0.5, 0};
  models[1].rigidBody.velocity = {v0 / std::sqrt(2.0), 0, v0 / std::sqrt(2.0)};
  const ours::World<T> w = world<T>(mu, 0);
  for (int n = 0; n < 120; ++n) ours::ApplyPhysics<T>(models, w, h);
  const ours::Vector3<T>& x = models[1].translation;
  CHECK(std::hypot(x.x(), x.z()) == Approx(2.509472).margin(1e-6));
  CHECK(x.x() == Approx(x.z()).margin(1e-12));
}

TEST_CASE("a sphere dropped 1 m hits at step 27 and leaves at e times its step-start approach",
          "[ours][collision]") {
  using T = double;
  const T h = T(1) / T(60), g = 9.8, e = 0.5;
  std::vector<ours::Model<T>> models(2);
  models[1] = floor_box<T>();
  models[0].translation = {0, 1.5, 0};
  models[0].collider.shape = ours::Shape::Sphere;
  models[0].collider.radius = 0.5;
  const ours::World<T> w = world<T>(0, e);
  int contact = -1;
  for (int n = 1; n <= 27; ++n) {
    ours::ApplyPhysics<T>(models, w, h);
    if (contact < 0 && models[0].translation.y() < 0.5) contact = n;
  }
  REQUIRE(contact == 27);
  const T depth = 0.5 - models[0].translation.y();
  CHECK(depth == Approx(g * h * h * 27 * 28 / 2 - 1.0).margin(1e-12));  // 0.029 m
  const T approach = -models[0].rigidBody.velocity.y();
  CHECK(approach == Approx(g * h * 27).margin(1e-12));  // 4.41 m/s
  ours::ApplyPhysics<T>(models, w, h);
  CHECK(models[0].rigidBody.velocity.y() == Approx(e * approach).margin(1e-12));
  CHECK(models[0].translation.y() == Approx(0.5 + h * e * approach).margin(1e-12));
}

TEST_CASE("a stack of two cubes on the floor stays exactly at rest", "[ours][collision]") {
  for (const float drag : {1.0f, 0.98f}) {
    std::vector<ours::Model<float>> models(3);
    models[0] = floor_box<float>();
    models[1].translation = {0, 0.75f, 0};
    models[1].collider.halfExtents = {0.75f, 0.75f, 0.75f};
    models[2].translation = {0, 2.0f, 0};
    ours::World<float> w = world<float>(0.5f, 0);
    w.linearDrag = drag;
    for (int n = 0; n < 600; ++n) ours::ApplyPhysics<float>(models, w, 1.0f / 60.0f);
    CHECK(models[1].translation == ours::Vector3<float>(0, 0.75f, 0));
    CHECK(models[2].translation == ours::Vector3<float>(0, 2.0f, 0));
    CHECK(models[1].rigidBody.velocity.isZero(0.0f));
    CHECK(models[2].rigidBody.velocity.isZero(0.0f));
  }
}

TEST_CASE("a cube dropped on the floor lands and rests at the floor's top, never in it",
          "[ours][collision]") {
  using T = double;
  std::vector<ours::Model<T>> models(2);
  models[0] = floor_box<T>();
  models[1].translation = {0, 10, 0};
  const ours::World<T> w = world<T>(0, 0);
  for (int n = 0; n < 300; ++n) ours::ApplyPhysics<T>(models, w, T(1) / T(60));
  CHECK(models[1].translation.y() == 0.5);
  CHECK(models[1].rigidBody.velocity.isZero(0.0));
}

TEST_CASE("with collisions off, the cubes fall through the floor as in Part III",
          "[ours][collision]") {
  using T = float;
  std::vector<ours::Model<T>> a(2);
  a[0] = floor_box<T>();
  std::vector<ours::Model<T>> b = a;
  a[1].translation = b[1].translation = {0, 1, 0};
  const ours::World<T> off;  // the seed's world: collisions off
  for (int n = 0; n < 120; ++n) {
    ours::ApplyPhysics<T>(a, off, ours::PHYSICS_TIMESTEP<T>);
    for (ours::Model<T>& m : b) {  // Part III's procedures, by hand
      if (m.rigidBody.isStatic) continue;
      ours::ApplyGravity(&m, off, ours::PHYSICS_TIMESTEP<T>);
      ours::IntegrateLinearForce(&m, off, ours::PHYSICS_TIMESTEP<T>);
      ours::IntegrateAngularForce(&m, off, ours::PHYSICS_TIMESTEP<T>);
    }
  }
  CHECK(a[1].translation.y() < -1.0f);  // through the floor
  CHECK(a[1].translation == b[1].translation);
  CHECK(a[1].rigidBody.velocity == b[1].rigidBody.velocity);
}

TEST_CASE("a turned cube landing on an edge turns by the closed form of one impulse at the edge",
          "[ours][collision]") {
  using T = double;
  const dropcheck::testing::EdgeLanding e;
  std::vector<ours::Model<T>> models(2);
  models[0] = floor_box<T>();
  models[1].translation = e.centre();
  models[1].rotation = e.rotation();
  models[1].rigidBody.velocity = {0, e.v0, 0};
  ours::ApplyPhysics<T>(models, world<T>(0, 0), e.h);
  const ours::RigidBody<T>& b = models[1].rigidBody;
  CHECK(b.velocity.y() == Approx(e.vy()).epsilon(1e-14));
  CHECK(b.angularVelocity.z() == Approx(e.wz()).epsilon(1e-14));
  CHECK(std::abs(b.velocity.x()) + std::abs(b.velocity.z()) < 1e-15);
  CHECK(std::abs(b.angularVelocity.x()) + std::abs(b.angularVelocity.y()) < 1e-15);
  // The edge's point no longer approaches: v_y + w_z*r_x = 0.
  CHECK(std::abs(b.velocity.y() + b.angularVelocity.z() * e.arm().x()) < 1e-14);
}

TEST_CASE("a tumbling cube lands, turns and stays above the floor", "[ours][collision]") {
  using T = double;
  std::vector<ours::Model<T>> models(2);
  models[0] = floor_box<T>();
  models[1].translation = {0, 3, 0};
  models[1].rigidBody.angularVelocity = {2, 3, 1};
  const ours::World<T> w = world<T>(T(0.5), T(0));
  for (int n = 0; n < 240; ++n) ours::ApplyPhysics<T>(models, w, T(1) / T(60));
  // Its centre ends between the resting heights on a face (0.5 m) and on a corner (sqrt(3)/2 m),
  // and it has turned away from its start.
  CHECK(models[1].translation.y() > 0.5 - 1e-9);
  CHECK(models[1].translation.y() < std::sqrt(3.0) / 2);
  CHECK(models[1].rotation.w() < 0.99);
}
