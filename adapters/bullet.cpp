// Adapter for Bullet (btDiscreteDynamicsWorld), linked against Debian's float64 or float build.
//
// Mapping (scene -> Bullet), docs/engines.md sections 2, 3 and 5:
//   gravity g           -> btDiscreteDynamicsWorld::setGravity (Bullet's default is (0, -10, 0)).
//   damping rate k      -> btRigidBody::setDamping(d = 1 - exp(-k), 0). btRigidBody::applyDamping
//                          does v *= (1 - d)^h, so d is "lost per second" and the per-step decay is
//                          (exp(-k))^h = exp(-k*h) at any h. Angular damping k_a the same way
//                          (d_a = 1 - exp(-k_a), applied to w in the same call, same limit).
//                          Limit: Bullet computes 1 - d in btScalar, and below 1 a btScalar has
//                          a spacing of 1.1e-16 (double) / 6e-8 (float). When exp(-k) is below
//                          half of it (k > 36.7 1/s in double, about 17 in float) d rounds to 1
//                          and Bullet would zero every velocity each step instead of decaying it
//                          by exp(-k*h): such scenes are refused (cannot_run, and load throws).
//   law                 -> DampingOrder::BeforeForces: predictUnconstraintMotion damps v, then the
//                          solver adds (m*g + F)*(1/m)*h, then integrateTransforms does x += h*v.
//   mass m, inertia     -> btRigidBody mass m, local inertia the scene's principal moments (by
//                          default those of a uniform box: Bullet's own box formula, up to
//                          rounding). Rotations stay free.
//   rotation            -> start transform's rotation btQuaternion(x, y, z, w); setAngularVelocity
//                          (world frame); applyTorque (world frame) before the step, cleared by
//                          clearForces. Read back: getWorldTransform().getRotation() (rebuilt from
//                          the basis matrix, which is Bullet's state) and getAngularVelocity().
//                          Law (btDiscreteDynamicsWorld.cpp, btRigidBody.cpp,
//                          btSequentialImpulseConstraintSolver.cpp, btTransformUtil.h): damping
//                          first (predictUnconstraintMotion), then the torque impulse h*I_w^-1*T
//                          and the default gyroscopic flag BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY
//                          (one Newton step in body coordinates, from the damped w) in the solver's
//                          setup, then integrateTransform: the exponential map, dq*q. So:
//                          implicit-body/exp-map, BeforeForces. Limit: integrateTransform clamps
//                          the turn of one step to pi/4 (ANGULAR_MOTION_THRESHOLD), |w|*h > 0.785:
//                          reported as a clamp (speed_clamped), where the own-law comparison ends.
//   static body         -> mass 0 (Bullet marks it CF_STATIC_OBJECT); read back as its fixed
//                          position and zero velocity.
//   position, velocity  -> start world transform, setLinearVelocity. No motion state at all: the
//                          state is read from getWorldTransform / getLinearVelocity, never from an
//                          interpolated btMotionState (one step stale with an accumulator).
//   force this step     -> applyCentralForce before the step; stepSimulation ends with
//                          btDiscreteDynamicsWorld::clearForces on every dynamic body, so each
//                          force acts on this step only.
//   one step            -> stepSimulation(h, 0): maxSubSteps = 0 is Bullet's variable-step mode,
//                          exactly one internal step of h, no accumulator, no interpolation.
//   sleeping            -> setActivationState(DISABLE_DEACTIVATION) on every body.
// Contacts (scene.world.contacts):
//   true  -> a btBoxShape per body with the scene's half extents (Bullet keeps its 0.04 m margin
//            inside them), or a btSphereShape of a sphere's radius; restitution sqrt(e) per body
//            for the scene's restitution e (0 when unset), friction sqrt(0.5) per body: Bullet
//            combines both as the product (btManifoldResult::calculateCombinedRestitution and
//            ::calculateCombinedFriction), so every pair gets e and mu = 0.5. A scene's friction
//            mu: with one dynamic body, mu on it and 1 on every static body (the product is mu
//            exactly); with more, sqrt(mu) on every body (mu to an ulp).
//            Friction (btSequentialImpulseConstraintSolver.cpp, 3.24: convertContact,
//            solveSingleIteration): one row per contact along that contact's slip before the
//            solve (SOLVER_USE_2_FRICTION_DIRECTIONS is off by default), solved after every
//            normal row in each of the 10 iterations and clamped to mu times the contact's
//            accumulated normal impulse; a row whose contact has no normal impulse is skipped,
//            keeping what earlier iterations gave it. A cone, held to Coulomb's law step by step
//            from the run's momentum (ContactSolverKind::bullet_3). Solver: sequential
//            impulse, 10 iterations (defaults), split impulse for every penetration:
//            m_splitImpulsePenetrationThreshold 0 instead of -0.04 m. Bullet's default pushes
//            penetrations shallower than 4 cm out with a Baumgarte velocity (ERP 0.2 * depth / h)
//            that stays in the body: the cube landing from 10 m rebounded 4 mm at 1/120 and 2.3 cm
//            at 1/240. Split impulse moves the body out without adding velocity: no rebound at any
//            step (bullet_test.cpp).
//   false -> one shared btEmptyShape (a btRigidBody needs some shape) and collision filter group
//            and mask 0, so the broadphase never pairs anything: no contact shapes, no contacts.
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adapters.hpp"
#include "harness/core/number_format.hpp"

namespace dropcheck {
namespace {

#ifdef BT_USE_DOUBLE_PRECISION
constexpr const char* kPrecision = "double";
constexpr Scalar kScalar = Scalar::f64;
#else
constexpr const char* kPrecision = "float";
constexpr Scalar kScalar = Scalar::f32;
#endif

// Combined friction of a pair (Bullet: product of the two bodies' coefficients).
constexpr double kFriction = 0.5;

btVector3 to_bt(const Vec3& v) {
  return {btScalar(v.x()), btScalar(v.y()), btScalar(v.z())};
}

Vec3 from_bt(const btVector3& v) {
  return {double(v.x()), double(v.y()), double(v.z())};
}

// Everything one loaded scene owns. Members are destroyed in reverse order: the world first (its
// destructor still touches the bodies' broadphase handles), then bodies, shapes, solver, ...
struct BulletWorld {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btEmptyShape empty_shape;
  std::vector<std::unique_ptr<btConvexInternalShape>> shapes;  // boxes and spheres
  std::vector<std::unique_ptr<btRigidBody>> bodies;            // indexed like Scene::bodies
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};

  ~BulletWorld() {
    for (auto& b : bodies) world.removeRigidBody(b.get());
  }
};

// The scene's principal moments (zero for a static body: Bullet ignores them at mass 0).
btVector3 local_inertia(const Body& b) {
  return b.is_static ? btVector3(0, 0, 0) : to_bt(inertia_of(b));
}

// Bullet's per-second damping for rate k: d = 1 - exp(-k), so that (1 - d)^h = exp(-k*h).
btScalar damping_fraction(double k) {
  return btScalar(1.0 - std::exp(-k));
}

// Digits of exp(-k) that survive in Bullet's 1 - d: d = 1 - exp(-k) is stored with an absolute
// error of up to eps/2 (d < 1), so 1 - d = exp(-k) carries a relative error up to
// (eps/2)/exp(-k), i.e. log10(2*exp(-k)/eps) digits. Double: 16 - 0.434*k digits, so k = 36.7 keeps
// none (d rounds to 1) and k = 30 only 2.9 (measured: 9.2 um off exp(-k*h) over free_fall_drag).
double damping_digits(double k) {
  const double eps = std::numeric_limits<btScalar>::epsilon();
  return std::log10(2.0 / eps) - k / std::log(10.0);
}

// Digits a damping parameter must keep after the engine forms it (Bullet: 1 - d, d = 1 - exp(-k)).
// Fewer and the engine's decay per step is a different physical rate than the scene's k:
// at k = 30 1/s Bullet keeps 2.9 digits and departs from exp(-k*h) by 9.2 um over free_fall_drag.
// Bullet in double then accepts k <= 22.9 1/s (the extreme stiff_spring_drag, k = 20, keeps 7.3).
inline constexpr double kMinParameterDigits = 6.0;

// Why Bullet cannot represent damping rate k to kMinParameterDigits digits; empty when
// it can. Double: k <= 22.9 1/s (float: about 2.2 1/s).
std::string damping_problem(double k) {
  const double digits = damping_digits(k);
  if (digits >= kMinParameterDigits) return {};
  const double k_max =
      (std::log10(2.0 / std::numeric_limits<btScalar>::epsilon()) - kMinParameterDigits) *
      std::log(10.0);
  return printf_string(
      "engine limit: damping rate k = %g 1/s: Bullet's per-second damping keeps 1 - d = "
      "exp(-k) to %.1f digits in %s (%g required: k <= %.1f 1/s), so its decay per step "
      "would not be exp(-k*h)",
      k, std::max(digits, 0.0), kPrecision, kMinParameterDigits, k_max);
}

// The same for both of the scene's damping rates, linear and angular.
std::string dampings_problem(const Scene& scene) {
  const std::string linear = damping_problem(scene.world.damping_rate);
  if (!linear.empty()) return linear;
  const std::string angular = damping_problem(scene.world.angular_damping_rate);
  return angular.empty() ? angular : "angular " + angular;
}

class BulletEngine final : public Engine {
 public:
  EngineInfo info() const override {
    EngineInfo i;
    i.name = "bullet";
    i.version = std::string(DROPCHECK_BULLET_VERSION) + " " + kPrecision;
    i.scalar = kScalar;
    i.capabilities = {.contacts = true,
                      .planar_only = false,
                      .rotation = Rotation::full,
                      .friction = true,
                      .restitution = true,
                      .spheres = true};
    i.law = DampingOrder::BeforeForces;
    i.rotation_law = {Gyroscopic::implicit_body, OrientationUpdate::exponential_map};
    i.arithmetic =
        DampingForm::per_second_power;  // its d = 1 - exp(-k), copied by own_arithmetic.cpp
    i.damping_mapping = "setDamping(d = 1 - exp(-k), d_a = 1 - exp(-k_a)); v *= (1-d)^h";
    i.contact_settings =
        "btBoxShape (margin 0.04 inside) or btSphereShape per body, restitution sqrt(e) each "
        "(product: e, 0 unset), friction sqrt(0.5) each (product: mu = 0.5; a scene's mu: mu on "
        "the "
        "one dynamic body and 1 on static ones, else sqrt(mu) each), sequential impulse 10 "
        "iterations, split impulse for every "
        "penetration (threshold 0)";
    // Measured on drop_on_floor(_undamped): final y - 0.5 = -3.2e-7 / -3.5e-7 m at 1/60, from
    // -1.3e-6 m (1/30) to -2e-8 m (1/240) over the sweep (bullet_test.cpp).
    // Its bounce, read in btSequentialImpulseConstraintSolver.cpp (setupContactConstraint,
    // restitutionCurve) and btCollisionDispatcher.cpp (getNewManifold): restitution of the
    // step-start approach above m_restitutionVelocityThreshold 0.2 m/s; a penetration pushed out
    // by split impulse at m_erp2 0.2 (position only, threshold 0 above); a contact found while the
    // gap is below gContactBreakingThreshold 0.02 times the smaller shape's bounding-sphere radius
    // (CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD, on by default), where the velocity target is
    // rest - gap/h. Measured on bounce_e01/05/09: 2.2e-16, 2.0e-15 and 1.7e-14 m from this law over
    // each run (bullet_test.cpp).
    i.bounce_law = {
        .erp = 0.2, .push_in_position = true, .threshold = 0.2, .contact_distance_per_size = 0.02};
    i.rest_offset = -3e-7;
    i.rest_tolerance = 2e-6;
    // A stack: 10 sweeps of sequential impulse (btContactSolverInfo::m_numIterations). They leave
    // the seed's two cubes unconverged through their rotation: measured on stack_rest at 1/60
    // over 5 s, the small cube drifts 4.45 mm, sinks 2.06e-5 m and still moves at 1.43e-3 m/s in
    // the last 2 s. The same stack in Bullet alone drifts 3.9 mm with 10 sweeps, 0.19 mm with 50
    // and 7.8e-13 m with 200 (docs/contact.md): the solver's residual, not the contact's law.
    i.stack_law = {.iterations = 10, .sink_bound = 5e-5, .drift_bound = 1e-2, .still_bound = 3e-3};
    // A slide: its friction is mu times the step's normal impulse while the box slides flat, but
    // a box rocking on its manifold's corners spreads the contacts' slip directions (a step's
    // friction along the slip up to 33 % short of mu*N) and a corner that loses its normal impulse
    // mid-step keeps its friction (up to 26 % over), on a minority of steps: over a whole slide
    // the friction is 0.997 to 1.067 of mu*N, but the median step's is mu*N to 1.9e-5 (43 slides:
    // slide_stop, incline_hold, incline_slide and slide_diagonal at 1/60, 1/120 and 1/240, and
    // scenarios/friction/); a coefficient 2 % off moves it to 0.98 or 1.02.
    i.friction_model = FrictionModel::cone;
    i.contact_solver = {.kind = ContactSolverKind::bullet_3,
                        .velocity_iterations = 10,
                        .coulomb_median_bound = 1e-3,
                        .keeps_stale_friction = true};
    // Bullet has CCD (btCollisionObject::setCcdMotionThreshold / setCcdSweptSphereRadius), but the
    // adapter leaves the threshold at its default 0, which disables it: overlap is tested at step
    // ends only.
    i.continuous_collision = false;
    return i;
  }

  bool use_body_materials() override { return body_materials_ = true; }

  std::string cannot_run(const Scene& scene) const override {
    const std::string why = Engine::cannot_run(scene);
    return why.empty() ? dampings_problem(scene) : why;
  }

  void load(const Scene& scene, double h) override {
    if (std::string why = dampings_problem(scene); !why.empty()) throw EngineError(why);
    w_.reset();
    w_ = std::make_unique<BulletWorld>();
    h_ = btScalar(h);
    w_->world.setGravity(to_bt(scene.world.gravity));
    // Position recovery by split impulse for any penetration depth (see the mapping at the top).
    w_->world.getSolverInfo().m_splitImpulsePenetrationThreshold = 0;
    restitution_ = scene_material(scene).restitution.value_or(0.0);
    friction_ = scene_material(scene).friction;
    dynamic_bodies_ = static_cast<int>(std::count_if(scene.bodies.begin(), scene.bodies.end(),
                                                     [](const Body& b) { return !b.is_static; }));
    for (const Body& b : scene.bodies) add_body(scene, b);
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t i = 0; i < w_->bodies.size(); ++i) {
      btRigidBody& b = *w_->bodies[i];
      if (!b.isStaticObject()) b.applyCentralForce(to_bt(forces[i]));
    }
  }

  void set_torques(std::span<const Vec3> torques) override {
    for (std::size_t i = 0; i < w_->bodies.size(); ++i) {
      btRigidBody& b = *w_->bodies[i];
      if (!b.isStaticObject()) b.applyTorque(to_bt(torques[i]));
    }
  }

  void step() override {
    // maxSubSteps = 0: exactly one internal step of h_ (no accumulator, no interpolation).
    w_->world.stepSimulation(h_, 0);
  }

  // Seconds of `steps` calls of stepSimulation alone (bare_step_loop in adapters.hpp).
  double bare_seconds(std::int64_t steps) {
    const auto start = std::chrono::steady_clock::now();
    for (std::int64_t n = 0; n < steps; ++n) w_->world.stepSimulation(h_, 0);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  void read(std::span<BodyState> out) const override {
    for (std::size_t i = 0; i < w_->bodies.size(); ++i) {
      const btRigidBody& b = *w_->bodies[i];
      out[i].position = from_bt(b.getWorldTransform().getOrigin());
      out[i].velocity = from_bt(b.getLinearVelocity());
    }
  }

  // True when integrateTransform clamped the last step's turn: it turns a body by at most
  // ANGULAR_MOTION_THRESHOLD (pi/4) per step, using the angular velocity the step ended with, and
  // tests fAngle*h > pi/4 with fAngle = sqrt(|w|^2) (btTransformUtil.h). The turn is then shorter
  // than the rotational law's (w itself is kept).
  bool speed_clamped() const override {
    for (const auto& b : w_->bodies) {
      if (b->isStaticObject()) continue;
      if (btSqrt(b->getAngularVelocity().length2()) * h_ > ANGULAR_MOTION_THRESHOLD) return true;
    }
    return false;
  }

  void read_rotation(std::span<RotationState> out) const override {
    for (std::size_t i = 0; i < w_->bodies.size(); ++i) {
      const btRigidBody& b = *w_->bodies[i];
      const btQuaternion q = b.getWorldTransform().getRotation();
      out[i].orientation = Quat(double(q.w()), double(q.x()), double(q.y()), double(q.z()));
      out[i].angular_velocity = from_bt(b.getAngularVelocity());
    }
  }

 private:
  btCollisionShape* shape_for(const Scene& scene, const Body& b) {
    if (!scene.world.contacts) return &w_->empty_shape;
    if (b.shape == Shape::sphere)
      w_->shapes.push_back(std::make_unique<btSphereShape>(btScalar(b.radius)));
    else
      w_->shapes.push_back(std::make_unique<btBoxShape>(to_bt(b.half_extents)));
    return w_->shapes.back().get();
  }

  void add_body(const Scene& scene, const Body& b) {
    const btScalar mass = b.is_static ? btScalar(0) : btScalar(b.mass);
    btTransform start;
    start.setIdentity();
    start.setOrigin(to_bt(b.position));
    const Quat& o = b.orientation;
    start.setRotation(
        btQuaternion(btScalar(o.x()), btScalar(o.y()), btScalar(o.z()), btScalar(o.w())));
    btRigidBody::btRigidBodyConstructionInfo ci(mass, nullptr, shape_for(scene, b),
                                                local_inertia(b));
    ci.m_startWorldTransform = start;
    ci.m_restitution = btScalar(std::sqrt(restitution_));
    ci.m_friction = friction_of(b);
    auto body = std::make_unique<btRigidBody>(ci);
    // dv/dt = -k*v over 1 s: v *= exp(-k), so d = 1 - exp(-k) is the fraction lost per second;
    // Bullet applies v *= (1 - d)^h per step = exp(-k*h).
    body->setDamping(damping_fraction(scene.world.damping_rate),
                     damping_fraction(scene.world.angular_damping_rate));
    body->setActivationState(DISABLE_DEACTIVATION);
    if (!b.is_static) body->setLinearVelocity(to_bt(b.velocity));
    if (!b.is_static) body->setAngularVelocity(to_bt(b.angular_velocity));
    if (scene.world.contacts)
      w_->world.addRigidBody(body.get());
    else
      w_->world.addRigidBody(body.get(), 0, 0);  // group 0, mask 0: never paired
    w_->bodies.push_back(std::move(body));
  }

  // Each body's friction, so that Bullet's product is the pair's mu (the mapping at the top).
  btScalar friction_of(const Body& b) const {
    // identify --combine: the body's own coefficient, Bullet's product makes the pair's.
    if (body_materials_ && b.friction) return btScalar(*b.friction);
    if (!friction_) return btScalar(std::sqrt(kFriction));
    if (dynamic_bodies_ == 1) return b.is_static ? btScalar(1) : btScalar(*friction_);
    return btScalar(std::sqrt(*friction_));
  }

  btScalar h_ = btScalar(1.0 / 60.0);
  double restitution_ = 0.0;  // the scene's e; each body gets sqrt(e) (Bullet multiplies the two)
  std::optional<double> friction_;  // the scene's mu, when it sets one
  int dynamic_bodies_ = 0;
  bool body_materials_ = false;  // Engine::use_body_materials
  std::unique_ptr<BulletWorld> w_;
};

}  // namespace

std::unique_ptr<Engine> make_bullet() {
  return std::make_unique<BulletEngine>();
}

double bare_seconds_bullet(const Scene& scene, double h) {
  BulletEngine e;
  e.load(scene, h);
  return e.bare_seconds(step_count(scene, h));
}

}  // namespace dropcheck
