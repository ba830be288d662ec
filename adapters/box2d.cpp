// Adapter for Box2D 2.4.1 (float, 2-D). Planar scenes only: the x-y plane, y up; z is dropped.
//
// Mapping (scene -> Box2D):
//   gravity g           -> b2World(gravity) (x, y), set explicitly
//   damping rate k      -> b2Body::SetLinearDamping(c), c = (exp(k*h) - 1)/h; angular damping 0.
//                          b2Island::Solve: v = (v + h*a)*1/(1 + h*c) and 1/(1 + h*c) = exp(-k*h),
//                          the same order as ours (DampingOrder::AfterForces)
//   cube, half extents  -> a square body of half extents (hx, hy); the scene's mass is the mass per
//                          unit depth: fixture density = m/(4*hx*hy), so that GetMass() = m
//                          (checked)
//   contacts = false    -> no fixture at all; b2Body::SetMassData gives mass m (a body without
//                          fixtures would have mass 1) and the box's inertia m*(hx^2 + hy^2)/3
//   static body         -> b2_staticBody (a polygon fixture only with contacts)
//   position, velocity  -> b2BodyDef::position, linearVelocity; read back with GetPosition() and
//                          GetLinearVelocity() after the step (no interpolation in Box2D)
//   force this step     -> ApplyForceToCenter(F) before Step; b2World::Step clears forces at its
//                          end (m_clearForces, SetAutoClearForces(true) set explicitly)
//   rotation (about z)  -> b2BodyDef::angle = 2*atan2(qz, qw), angularVelocity = w_z,
//                          angularDamping c_a = (exp(k_a*h) - 1)/h, ApplyTorque(tau_z) before the
//                          step, inertia the scene's I_z (SetMassData, also over a fixture's own).
//                          Read back as q = (cos(a/2), 0, 0, sin(a/2)) from GetAngle() and w_z
//                          from GetAngularVelocity(). Law (b2_island.cpp, b2Island::Solve):
//                          w += h*invI*T; w *= 1/(1 + h*c_a); a += h*w: the exact turn by h*w, so
//                          the exponential map, and no gyroscopic term (about a principal axis it
//                          is zero for every member). Limit: a turn above b2_maxRotation (pi/2) per
//                          step is clamped, |w|*h > 1.57. Rotations about x or y are not run.
//   sleeping            -> off: b2World::SetAllowSleeping(false) and b2BodyDef::allowSleep = false
//   one step            -> one b2World::Step(h, 8, 3)
// Speed clamp: b2Island::Solve scales v so that |h*v| <= b2_maxTranslation (2 m per step, 120 m/s
// at 60 Hz) and stores the clamped v; speed_clamped() reports the steps where that happened, seen
// before the step (Box2D's own velocity update, predicted: catches a clamp that continuous
// collision then hides by stopping the body) or after it (|h*v| at the limit).
// Contacts: polygon boxes or circles (spheres), the scene's friction (0.5 unset; mixed as
// sqrt(f1*f2)) and restitution (0 unset; mixed as the larger) on every fixture, so every pair gets
// them: harness/core/box2d_world.hpp. Every polygon has a
// b2_polygonRadius = 0.01 m skin and the solver keeps b2_linearSlop = 0.005 m of overlap, so a
// resting box's centre sits about 0.015 m above the geometric rest height (docs/engines.md 5).
#include <box2d/box2d.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "adapters.hpp"
#include "harness/core/box2d_world.hpp"

namespace dropcheck {
namespace {

// Box2D's recommended iteration counts (b2World::Step documentation).
constexpr int32 kVelocityIterations = 8;
constexpr int32 kPositionIterations = 3;

// Resting centre above floor top + half extent: the two skins (2*0.01 m) less the allowed slop
// (0.005 m) = 0.015 m; measured +0.0149996 m (unit cube dropped from 10 m on a box floor, with and
// without drag, at 1/30 .. 1/240, after 5 s).
constexpr double kRestOffset = 0.015;
// Measured |rest - 0.015| <= 3.7e-7 m over those runs.
constexpr double kRestTolerance = 1e-4;

// A clamped step leaves |h*v| = b2_maxTranslation up to float rounding (ratio = 2/|h*v|, then
// v*ratio): measured within 1.9e-7 of it on clamped steps (120.5 .. 5000 m/s at 60 Hz). A body
// whose |h*v| lies within this band below the limit is reported too (speeds within 1e-5 of it).
constexpr float kClampBand = 1e-5f;

b2Vec2 to_b2(const Vec3& v) {
  return {static_cast<float>(v.x()), static_cast<float>(v.y())};
}

class Box2dEngine final : public Engine {
 public:
  EngineInfo info() const override;
  void load(const Scene& scene, double h) override;
  void set_forces(std::span<const Vec3> forces) override;
  void set_torques(std::span<const Vec3> torques) override;
  void step() override;
  void read(std::span<BodyState> out) const override;
  void read_rotation(std::span<RotationState> out) const override;
  bool speed_clamped() const override { return clamped_; }
  bool use_body_materials() override { return body_materials_ = true; }

  // Seconds of `steps` calls of b2World::Step alone (bare_step_loop in adapters.hpp).
  double bare_seconds(std::int64_t steps);

  // Box2D's mass of body i (kg per unit depth), for tests.
  float mass_of(std::size_t i) const { return bodies_.at(i)->GetMass(); }

 private:
  b2Body* create_body(const Body& body, const Box2dBox& box);
  void set_box_mass(b2Body* b, const Body& body, bool fixture);
  bool clamp_ahead() const;
  bool clamped_after() const;

  std::unique_ptr<b2World> world_;
  std::vector<b2Body*> bodies_;  // owned by world_, indexed like Scene::bodies
  std::vector<b2Vec2> forces_;
  std::vector<float> torques_;
  bool rotating_ = false;  // the scene needs rotation: the scene's inertia is set over a fixture's
  float h_ = 1.0f / 60.0f;
  bool contacts_ = false;
  bool body_materials_ = false;  // Engine::use_body_materials
  bool clamped_ = false;
};

EngineInfo Box2dEngine::info() const {
  EngineInfo i;
  i.name = "box2d";
#ifdef DROPCHECK_BOX2D_VERSION
  i.version = DROPCHECK_BOX2D_VERSION;  // the package's; b2_version says 2.4.0 in 2.4.1
#else
  i.version = std::to_string(b2_version.major) + "." + std::to_string(b2_version.minor) + "." +
              std::to_string(b2_version.revision);
#endif
  i.scalar = Scalar::f32;
  i.capabilities = {.contacts = true,
                    .planar_only = true,
                    .rotation = Rotation::spin_z,
                    .friction = true,
                    .restitution = true,
                    .spheres = true};
  i.law = DampingOrder::AfterForces;
  i.rotation_law = {Gyroscopic::none, OrientationUpdate::exponential_map};
  i.arithmetic = DampingForm::pade;  // b2Island::Solve's float order, copied by own_arithmetic.cpp
  i.damping_mapping = "SetLinearDamping(c), c = (exp(k*h) - 1)/h; v = (v + a*h)/(1 + h*c)";
  i.contact_settings =
      "polygon boxes (0.01 m skin, 0.005 m slop) or circles, the scene's friction (0.5 unset; "
      "sqrt mix) and restitution (0 unset; max mix, threshold 1 m/s) on each fixture, 8 "
      "velocity / 3 position iterations, continuous collision on";
  // Its contact solver, read in b2_contact_solver.cpp (b2ContactSolver::SolveVelocityConstraints:
  // each point's friction clamped by mu times its accumulated normal impulse, then the normal
  // block) and b2_island.cpp (b2Island::Solve): replayed by harness/oracles/box2d_step.hpp.
  i.contact_solver = {.kind = ContactSolverKind::box2d_2_4,
                      .velocity_iterations = kVelocityIterations,
                      .position_iterations = kPositionIterations};
  i.rest_offset = kRestOffset;
  i.rest_tolerance = kRestTolerance;
  // A stack: 8 velocity iterations of sequential impulse (b2World::Step's velocityIterations).
  // Measured on stack_rest at 1/60: 1.6e-6 and 3.6e-6 m below its skins (f32), drift 1.4e-5 m.
  i.stack_law = {.iterations = 8, .sink_bound = 1e-5};
  // Continuous collision: b2World's constructor sets m_continuousPhysics = true (b2_world.cpp) and
  // the adapter keeps it; b2World::SolveTOI sweeps every contact with a non-dynamic body
  // (collideA = bA->IsBullet() || typeA != b2_dynamicBody), so a dynamic body against the static
  // floor is caught between step ends without setting b2BodyDef::bullet (b2_body.h).
  i.continuous_collision = true;
  return i;
}

void Box2dEngine::load(const Scene& scene, double h) {
  if (!is_planar(scene)) throw EngineError("not planar");
  h_ = static_cast<float>(h);
  contacts_ = scene.world.contacts;
  clamped_ = false;
  bodies_.clear();  // bodies belong to the old world, destroyed next
  const Box2dWorld world = box2d_world(scene, h, body_materials_);
  world_ = std::make_unique<b2World>(b2Vec2(world.gx, world.gy));
  world_->SetAllowSleeping(false);
  world_->SetAutoClearForces(true);
  // Box2D's float 1/(1 + h*c) (box2d_world's damping) can only take values 1.2e-7 apart (the ulp
  // of 1 + h*c): it lands 1.9e-8 from exp(-k*h) at 1/60 and 4.0e-8 at 1/240, the closest
  // reachable (no other float c does better).
  rotating_ = needs_rotation(scene);
  for (std::size_t i = 0; i < scene.bodies.size(); ++i)
    bodies_.push_back(create_body(scene.bodies[i], world.bodies[i]));
  forces_.assign(bodies_.size(), b2Vec2(0.0f, 0.0f));
  torques_.assign(bodies_.size(), 0.0f);
}

b2Body* Box2dEngine::create_body(const Body& body, const Box2dBox& box) {
  b2BodyDef def;
  def.type = box.is_static ? b2_staticBody : b2_dynamicBody;
  def.position.Set(box.x, box.y);
  def.linearVelocity.Set(box.vx, box.vy);
  def.linearDamping = box.linear_damping;
  def.angularDamping = box.angular_damping;
  def.angle = box.angle;
  def.angularVelocity = box.w;
  def.allowSleep = false;
  def.awake = true;
  b2Body* b = world_->CreateBody(&def);
  if (contacts_) {
    b2PolygonShape polygon;
    polygon.SetAsBox(box.hx, box.hy);
    b2CircleShape circle;
    circle.m_radius = box.radius;  // centred on the body (m_p = 0)
    b2FixtureDef fixture;
    fixture.shape = box.radius > 0.0f ? static_cast<const b2Shape*>(&circle) : &polygon;
    fixture.density = box.density;
    fixture.friction = box.friction;
    fixture.restitution = box.restitution;
    b->CreateFixture(&fixture);
  }
  if (!body.is_static) set_box_mass(b, body, contacts_);
  return b;
}

// With a fixture: check that density*area gave the scene's mass. Without: set it (Box2D gives a
// dynamic body without fixtures mass 1).
void Box2dEngine::set_box_mass(b2Body* b, const Body& body, bool fixture) {
  const double m = body.mass;
  if (!fixture || rotating_) {
    // The scene's moment about z (a fixture's own moment is kept when nothing turns the body:
    // contacts then see exactly Box2D's box).
    b2MassData data;
    data.mass = fixture ? b->GetMass() : static_cast<float>(m);
    data.center.SetZero();
    data.I = static_cast<float>(inertia_of(body).z());
    b->SetMassData(&data);
  }
  // float area and density: measured relative error 0 for the scenes in scenarios/.
  if (std::abs(b->GetMass() - m) > 1e-6 * m)
    throw EngineError("Box2D mass " + std::to_string(b->GetMass()) + " != scene mass " +
                      std::to_string(m));
}

void Box2dEngine::set_forces(std::span<const Vec3> forces) {
  for (std::size_t i = 0; i < forces_.size(); ++i) forces_[i] = to_b2(forces[i]);
}

void Box2dEngine::set_torques(std::span<const Vec3> torques) {
  for (std::size_t i = 0; i < torques_.size(); ++i)
    torques_[i] = static_cast<float>(torques[i].z());
}

void Box2dEngine::step() {
  const bool ahead = clamp_ahead();
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_[i]->GetType() == b2_dynamicBody) {
      bodies_[i]->ApplyForceToCenter(forces_[i], true);
      if (torques_[i] != 0.0f) bodies_[i]->ApplyTorque(torques_[i], true);
    }
    forces_[i].SetZero();  // this step only (Engine::set_forces)
    torques_[i] = 0.0f;
  }
  world_->Step(h_, kVelocityIterations, kPositionIterations);
  clamped_ = ahead || clamped_after();
}

// Before the step: the velocity b2Island::Solve will reach before its clamp, computed as it does
//   v += h*invMass*(gravityScale*mass*g + F);  v *= 1/(1 + h*c)
// and its test |h*v|^2 > b2_maxTranslationSquared. Exact unless a contact changes v first; it sees
// a clamp that continuous collision (SolveTOI) later hides by stopping the body.
bool Box2dEngine::clamp_ahead() const {
  const b2Vec2 g = world_->GetGravity();
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const b2Body* b = bodies_[i];
    if (b->GetType() != b2_dynamicBody) continue;
    const float mass = b->GetMass();
    b2Vec2 v = b->GetLinearVelocity();
    v += h_ * (1.0f / mass) * (b->GetGravityScale() * mass * g + forces_[i]);
    v *= 1.0f / (1.0f + h_ * b->GetLinearDamping());
    const b2Vec2 travel = h_ * v;
    if (b2Dot(travel, travel) > b2_maxTranslationSquared) return true;
    // The same for the turn: w += h*invI*T; w *= 1/(1 + h*c_a); clamped when (h*w)^2 exceeds
    // b2_maxRotationSquared (b2Island::Solve).
    const float inv_i = b->GetInertia() > 0.0f ? 1.0f / b->GetInertia() : 0.0f;  // as m_invI
    float w = b->GetAngularVelocity() + h_ * inv_i * torques_[i];
    w *= 1.0f / (1.0f + h_ * b->GetAngularDamping());
    const float turn = h_ * w;
    if (turn * turn > b2_maxRotationSquared) return true;
  }
  return false;
}

// After the step: a clamp in b2Island::Solve (if |h*v|^2 > b2_maxTranslationSquared then
// v *= b2_maxTranslation/|h*v|) leaves |h*v| = b2_maxTranslation up to rounding (kClampBand). This
// sees clamps of velocities that contacts raised during the step.
bool Box2dEngine::clamped_after() const {
  for (const b2Body* b : bodies_) {
    if (b->GetType() != b2_dynamicBody) continue;
    const float travel = (h_ * b->GetLinearVelocity()).Length();
    if (travel >= b2_maxTranslation * (1.0f - kClampBand)) return true;
    if (std::abs(h_ * b->GetAngularVelocity()) >= b2_maxRotation * (1.0f - kClampBand)) return true;
  }
  return false;
}

double Box2dEngine::bare_seconds(std::int64_t steps) {
  const auto start = std::chrono::steady_clock::now();
  for (std::int64_t n = 0; n < steps; ++n)
    world_->Step(h_, kVelocityIterations, kPositionIterations);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void Box2dEngine::read(std::span<BodyState> out) const {
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    const b2Vec2 p = bodies_[i]->GetPosition();
    const b2Vec2 v = bodies_[i]->GetLinearVelocity();
    out[i].position = Vec3(p.x, p.y, 0.0);
    out[i].velocity = Vec3(v.x, v.y, 0.0);
  }
}

void Box2dEngine::read_rotation(std::span<RotationState> out) const {
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    out[i] = turn_about_z(bodies_[i]->GetAngle(), bodies_[i]->GetAngularVelocity());
}

}  // namespace

std::unique_ptr<Engine> make_box2d() {
  return std::make_unique<Box2dEngine>();
}

double bare_seconds_box2d(const Scene& scene, double h) {
  Box2dEngine e;
  e.load(scene, h);
  return e.bare_seconds(step_count(scene, h));
}

// For tests (tests/adapters/box2d_test.cpp): Box2D's GetMass() of body i of a loaded box2d engine.
double box2d_body_mass(const Engine& engine, std::size_t body) {
  return dynamic_cast<const Box2dEngine&>(engine).mass_of(body);
}

}  // namespace dropcheck
