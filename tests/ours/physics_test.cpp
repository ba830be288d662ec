// Tests ours/physics.hpp and ours/constants.hpp: the seed's step against its exact discrete
// solution.
//
// Discrete law of one step (docs/engines.md section 1), acceleration a = g + F/m constant, b = a*h:
//   v_{n+1} = f*(v_n + b);  x_{n+1} = x_n + h*v_{n+1}
// Fixed point v* = f*b/(1 - f), so v_n - v* = f^n*(v0 - v*):
//   v_n = f^n*v0 + f*b*(1 - f^n)/(1 - f)
// Summing x_n = x0 + h*sum_{j=1..n} v_j with sum_{j=1..n} f^j = f*(1 - f^n)/(1 - f):
//   x_n = x0 + h*v0*f*(1 - f^n)/(1 - f) + h*f*b/(1 - f)*[n - f*(1 - f^n)/(1 - f)]
// For v0 = 0 and F = 0 this is docs/engines.md's form (its "a" is our b = g*h).
// No drag (f = 1): v_n = v0 + n*b;  x_n = x0 + v0*n*h + a*h^2*n*(n + 1)/2.
// The reference is evaluated in long double from the same (already rounded) constants the
// iteration uses, so the difference is the iteration's own rounding only.
#include "ours/physics.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

namespace {

using LD = long double;

struct PhysicsCase {
  double x0, v0, accel_g, force, mass, drag;  // one axis; accel_g is g along it
};

// Exact discrete solution after n steps (header comment), one axis.
template <typename T>
void physics_closed_form(const PhysicsCase& c, T h_t, int n, LD& x, LD& v) {
  const LD h = h_t, f = static_cast<T>(c.drag), x0 = static_cast<T>(c.x0),
           v0 = static_cast<T>(c.v0);
  const LD a =
      LD(static_cast<T>(c.accel_g)) + LD(static_cast<T>(c.force)) / LD(static_cast<T>(c.mass));
  const LD b = a * h;
  if (f == 1) {
    v = v0 + n * b;
    x = x0 + v0 * n * h + a * h * h * n * (n + 1) / 2;
    return;
  }
  const LD fn = std::pow(f, LD(n)), geo = f * (1 - fn) / (1 - f);
  v = fn * v0 + f * b * (1 - fn) / (1 - f);
  x = x0 + h * v0 * geo + h * f * b / (1 - f) * (n - geo);
}

// Runs `steps` steps of ApplyPhysics with the case on every axis scaled by (1, -1, 0.5) and
// returns the worst |x - closed form| and |v - closed form| over all steps and axes.
template <typename T>
void physics_worst_error(const PhysicsCase& c, int steps, T h, double& dx, double& dv,
                         double& max_x, double& max_v) {
  const Eigen::Vector3d scale(1.0, -1.0, 0.5);
  std::vector<ours::Model<T>> models(1);
  models[0].translation = (c.x0 * scale).cast<T>();
  models[0].rigidBody.velocity = (c.v0 * scale).cast<T>();
  models[0].rigidBody.mass = static_cast<T>(c.mass);
  ours::World<T> world;
  world.gravity = (c.accel_g * scale).cast<T>();
  world.linearDrag = static_cast<T>(c.drag);
  dx = dv = max_x = max_v = 0;
  for (int n = 1; n <= steps; ++n) {
    models[0].rigidBody.force =
        (c.force * scale).cast<T>();  // the accumulator is cleared each step
    ours::ApplyPhysics<T>(models, world, h);
    for (int i = 0; i < 3; ++i) {
      PhysicsCase ci{c.x0 * scale[i],    c.v0 * scale[i], c.accel_g * scale[i],
                     c.force * scale[i], c.mass,          c.drag};
      LD x, v;
      physics_closed_form<T>(ci, h, n, x, v);
      dx = std::max(dx, double(std::fabs(LD(models[0].translation[i]) - x)));
      dv = std::max(dv, double(std::fabs(LD(models[0].rigidBody.velocity[i]) - v)));
      max_x = std::max(max_x, double(std::fabs(x)));
      max_v = std::max(max_v, double(std::fabs(v)));
    }
  }
}

// Float rounding bound. Each float operation has relative error <= u = 2^-24. Per step the velocity
// takes about 5 rounded operations (g*h, +, F/m*h, +, *f) of size <= V = max|v| + |a|*h, and f <= 1
// does not amplify old errors, so |dv_n| <= 5*n*u*V. The position adds u*(|x| + h*|v|) per step
// plus h*|dv_j| carried: |dx_n| <= n*u*(X + h*V) + h*5*u*V*n*(n+1)/2 <= n*u*(X + 3*(n + 1)*h*V). A
// worst case: roundings of either sign partly cancel, so the measured error sits 20-100x below.
struct Bound {
  double x, v;
};
Bound float_bound(int n, double h, double max_x, double max_v) {
  const double u = std::ldexp(1.0, -24);
  return {n * u * (max_x + 3.0 * (n + 1) * h * max_v), 5.0 * n * u * max_v};
}

const PhysicsCase kNoDrag{10.0, 0.0, -9.8, 0.0, 1.0, 1.0};
const PhysicsCase kSeedDrag{10.0, 0.0, -9.8, 0.0, 1.0, 0.98};
const PhysicsCase kForceAndV0{1.0, 8.0, -9.8, 7.0, 2.5, 0.98};  // mass != 1, v0 != 0, drag
const PhysicsCase kForceAndV0NoDrag{1.0, 8.0, -9.8, 7.0, 2.5, 1.0};

}  // namespace

TEST_CASE("the seed's constants are 1/60 s, (0, -9.8, 0) and 0.98 in float and double", "[ours]") {
  CHECK(ours::PHYSICS_TIMESTEP<double> == 1.0 / 60.0);
  CHECK(ours::PHYSICS_TIMESTEP<float> == 1.0f / 60.0f);
  CHECK(ours::GRAVITY<double> == Eigen::Vector3d(0.0, -9.8, 0.0));
  CHECK(ours::GRAVITY<float> == Eigen::Vector3f(0.0f, -9.8f, 0.0f));
  CHECK(ours::LINEAR_DRAG<double> == 0.98);
  CHECK(ours::LINEAR_DRAG<float> == 0.98f);
  // The seed's defaults: mass 1, not static, and a World that uses the constants.
  const ours::World<float> w;
  CHECK(w.gravity == ours::GRAVITY<float>);
  CHECK(w.linearDrag == ours::LINEAR_DRAG<float>);
  const ours::RigidBody<float> b;
  CHECK(b.mass == 1.0f);
  CHECK_FALSE(b.isStatic);
}

TEST_CASE(
    "ApplyPhysics in double matches the closed form to 1e-12: no drag (x0 + v0*n*h + "
    "a*h^2*n(n+1)/2), the seed's drag, a constant force with mass 2.5 and v0 != 0",
    "[ours]") {
  // Each row: the case, its steps at 1/60, and the measured worst |dx| and |dv|.
  struct Row {
    const char* what;
    PhysicsCase c;
    int steps;
    const char* measured;
  };
  const Row r = GENERATE(
      Row{"no drag", kNoDrag, 120, "dx 1.5e-14, dv 3.6e-14"},
      Row{"a force, mass 2.5 and v0, no drag", kForceAndV0NoDrag, 120, "dx 3.8e-14, dv 3.6e-14"},
      Row{"the seed's drag", kSeedDrag, 300, "dx 2.7e-14, dv 1.3e-14"},
      Row{"a force, mass 2.5 and v0, with drag", kForceAndV0, 300, "dx 7.1e-14, dv 2.2e-14"});
  double dx, dv, mx, mv;
  physics_worst_error<double>(r.c, r.steps, 1.0 / 60.0, dx, dv, mx, mv);
  INFO(r.what << ", " << r.steps << " steps (measured " << r.measured << ")");
  CHECK(dx < 1e-12);
  CHECK(dv < 1e-12);
}

TEST_CASE("ApplyPhysics in float stays within the float rounding bound of the closed form",
          "[ours]") {
  for (const PhysicsCase& c : {kNoDrag, kSeedDrag, kForceAndV0, kForceAndV0NoDrag}) {
    const int n = 300;
    double dx, dv, mx, mv;
    physics_worst_error<float>(c, n, ours::PHYSICS_TIMESTEP<float>, dx, dv, mx, mv);
    const Bound b = float_bound(n, 1.0 / 60.0, mx, mv + 9.8 / 60.0 + 7.0 / 2.5 / 60.0);
    INFO("drag " << c.drag << ": dx " << dx << " (bound " << b.x << "), dv " << dv << " (bound "
                 << b.v << ")");
    CHECK(dx < b.x);  // measured 1.2e-5 .. 1.3e-4 against bounds 2.4e-3 .. 1.5e-2
    CHECK(dv < b.v);  // measured 6.8e-6 .. 9.2e-5 against bounds 7.1e-4 .. 4.4e-3
    CHECK(dx > 0.0);  // float really rounds: the comparison is not vacuous
  }
}

TEST_CASE(
    "60 steps of the seed's scene reproduce docs/engines.md's 6.5878983508563724 and "
    "6.5878987312316895",
    "[ours]") {
  std::vector<ours::Model<double>> d(1);
  std::vector<ours::Model<float>> f(1);
  d[0].translation = {0.0, 10.0, 0.0};
  f[0].translation = {0.0f, 10.0f, 0.0f};
  for (int n = 0; n < 60; ++n) {
    ours::ApplyPhysics<double>(d, {}, ours::PHYSICS_TIMESTEP<double>);
    ours::ApplyPhysics<float>(f, {}, ours::PHYSICS_TIMESTEP<float>);
  }
  CHECK(d[0].translation.y() == 6.5878983508563724);
  CHECK(double(f[0].translation.y()) == 6.5878987312316895);
  CHECK(d[0].translation.x() == 0.0);
  CHECK(d[0].translation.z() == 0.0);
}

TEST_CASE("a static body does not move even with a velocity and a force", "[ours]") {
  std::vector<ours::Model<double>> m(2);
  for (auto& model : m) {
    model.translation = {1.0, 2.0, 3.0};
    model.rigidBody.velocity = {4.0, 5.0, 6.0};
    model.rigidBody.force = {7.0, 8.0, 9.0};
  }
  m[0].rigidBody.isStatic = true;
  ours::ApplyPhysics<double>(m, {}, 1.0 / 60.0);
  CHECK(m[0].translation == Eigen::Vector3d(1.0, 2.0, 3.0));
  CHECK(m[0].rigidBody.velocity == Eigen::Vector3d(4.0, 5.0, 6.0));
  CHECK(m[1].translation != Eigen::Vector3d(1.0, 2.0, 3.0));  // the dynamic twin does move
}

TEST_CASE("the force accumulator is cleared by a step and acts on that step only",
          "[ours][accumulator]") {
  std::vector<ours::Model<double>> m(1);
  const ours::World<double> w{Eigen::Vector3d::Zero(), 1.0};
  const double h = 0.5;
  m[0].rigidBody.mass = 2.0;
  m[0].rigidBody.force = {4.0, 0.0, 0.0};
  ours::ApplyPhysics<double>(m, w, h);
  CHECK(m[0].rigidBody.force == Eigen::Vector3d::Zero());
  CHECK(m[0].rigidBody.velocity.x() == 1.0);  // v = F/m*h = 4/2*0.5
  ours::ApplyPhysics<double>(m, w, h);        // no force re-applied: velocity stays
  CHECK(m[0].rigidBody.velocity.x() == 1.0);
  CHECK(m[0].translation.x() == 1.0);  // x = h*1 + h*1
}
