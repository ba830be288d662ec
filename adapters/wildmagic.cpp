// Adapter for Wild Magic 5.17's RigidBody<double> (Debian's libwildmagic-dev, Geometric Tools'
// physics library): a single rigid body advanced by classical fourth-order Runge-Kutta, the one
// high-order engine dropcheck compares. Wild Magic has no world: the adapter keeps one RigidBody
// per dynamic body and calls Update on each in turn.
//
// Mapping (scene -> Wild Magic), read in Wild Magic 5.17's LibPhysics/RigidBody/Wm5RigidBody.cpp
// and its header:
//   law                 -> RigidBody::Update(t, h): four stages on the state (x, q, P, L), each
//                          evaluating the force and torque callbacks at the stage's state (A1 at
//                          t, A2 and A3 at t + h/2 from S0 + (h/2)*A1 and S0 + (h/2)*A2, A4 at
//                          t + h from S0 + h*A3), then S1 = S0 + (h/6)*(A1 + 2*(A2 + A3) + A4), v =
//                          P/m: the RK4 member of the law family (kRungeKutta4).
//   mass m              -> SetMass(float): the mass is stored as float(m) (the parameter is a
//                          float even for RigidBody<double>). Every force the callback returns is
//                          scaled by float(m)/m, so the acceleration is the scene's F/m to
//                          rounding, whatever the mass.
//   gravity g           -> part of the force callback: float(m)*g (Wild Magic has no gravity).
//   damping rate k      -> part of the force callback: -k*P, the continuous drag, evaluated at
//                          each stage; per step a velocity keeps R(k*h) = 1 - u + u^2/2 - u^3/6 +
//                          u^4/24 (u = k*h), exp(-k*h) to O(u^5).
//   force this step     -> the force callback adds the step-start force the harness handed over,
//                          plus each spring's change from the step start to the stage
//                          (stage_force, harness/core/forces.hpp): RK4 with its forces frozen at
//                          the step start would be first order, and forward Euler's unstable
//                          kind on an undamped spring. The callback has no user pointer, so it
//                          reads the body being updated from a thread_local set around Update.
//                          The force applies to one step (the harness's contract).
//   inertia             -> SetBodyInertia(diag(I)): the scene's principal moments (double).
//   orientation, spin   -> SetQOrientation(q), then SetAngularVelocity(w) (L = R*I*R^T*w); read
//                          back from the body's own mQuatOrient and mAngularVelocity (=
//                          R*I^-1*R^T*L after each step). Update never renormalises q: it is
//                          reported as it is, and the law (kRotationRk4,
//                          harness/core/rotation_law.hpp) keeps it so.
//   torque, k_a         -> the torque callback returns this step's torque (world frame) minus
//                          k_a*L: the angular drag at each stage, as the linear one. Without
//                          torque L is constant: torque-free angular momentum is conserved by
//                          construction.
//   position, velocity  -> SetPosition, SetLinearVelocity (P = float(m)*v); read back from the
//                          body's own mPosition and mLinearVelocity (= P/float(m), derived after
//                          each step) through a subclass, without a library call per number.
//   static body         -> no RigidBody: read back at its position, at rest.
//   time t              -> n*h, passed to Update (the callbacks ignore it).
// Contacts: Wild Magic's physics library has no collision pipeline for RigidBody: a scene with
// contacts is not run.
#include <Wm5RigidBody.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "adapters.hpp"
#include "harness/core/engine_writer.hpp"
#include "harness/core/forces.hpp"

namespace dropcheck {
namespace {

using WmVec = Wm5::Vector3d;

WmVec to_wm(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

Vec3 from_wm(const WmVec& v) {
  return {v.X(), v.Y(), v.Z()};
}

// A RigidBody whose state the adapter reads without a library call (the getters are compiled into
// libWm5Physics, not inline).
struct WmBody : Wm5::RigidBodyd {
  const WmVec& x() const { return mPosition; }
  const WmVec& v() const { return mLinearVelocity; }
  const Wm5::Quaterniond& q() const { return mQuatOrient; }
  const WmVec& w() const { return mAngularVelocity; }
};

// What the force callback needs of the body being updated.
struct ForceContext {
  Vec3 gravity = Vec3::Zero();
  double rate = 0.0;                   // k, 1/s
  double scale = 1.0;                  // float(m)/m
  Vec3 force = Vec3::Zero();           // this step's force from the harness (N)
  Vec3 torque = Vec3::Zero();          // this step's torque from the harness (N m, world)
  double angular_rate = 0.0;           // k_a, 1/s
  BodyState start;                     // the body's state at the step start
  std::vector<const Spring*> springs;  // the springs on it (stage_force)
};

thread_local const ForceContext* t_current = nullptr;

// Wild Magic's force callback: dP/dt at a stage's state (see the top of this file).
WmVec force_at_stage(double, double mass, const WmVec& x, const Wm5::Quaterniond&,
                     const WmVec& momentum, const WmVec&, const Wm5::Matrix3d&, const WmVec& v,
                     const WmVec&) {
  const ForceContext& c = *t_current;
  const Vec3 f = stage_force(c.force, c.springs, c.start, {from_wm(x), from_wm(v)});
  return to_wm(mass * c.gravity + c.scale * f - c.rate * from_wm(momentum));
}

// Wild Magic's torque callback: dL/dt at a stage's state.
WmVec torque_at_stage(double, double, const WmVec&, const Wm5::Quaterniond&, const WmVec&,
                      const WmVec& momentum, const Wm5::Matrix3d&, const WmVec&, const WmVec&) {
  const ForceContext& c = *t_current;
  return to_wm(c.torque - c.angular_rate * from_wm(momentum));
}

class WildMagicEngine final : public Engine {
 public:
  EngineInfo info() const override {
    EngineInfo i;
    i.name = "wildmagic";
    i.version = DROPCHECK_WILDMAGIC_VERSION;
    i.scalar = Scalar::f64;
    i.capabilities = {.contacts = false, .planar_only = false, .rotation = Rotation::full};
    i.law = kRungeKutta4;
    i.rotation_law = kRotationRk4;
    i.damping_mapping =
        "force -k*P at each RK4 stage; per step v keeps 1 - u + u^2/2 - u^3/6 + "
        "u^4/24, u = k*h";
    return i;
  }

  void load(const Scene& scene, double h) override {
    h_ = h;
    steps_ = 0;
    bodies_.clear();
    contexts_.clear();
    index_.clear();
    statics_.clear();
    const auto springs = springs_by_body(scene);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      if (b.is_static) {
        statics_.push_back({i, b.position, b.orientation});
        continue;
      }
      auto body = std::make_unique<WmBody>();
      body->SetMass(static_cast<float>(b.mass));
      const Vec3 inertia = inertia_of(b);
      body->SetBodyInertia(Wm5::Matrix3d(inertia.x(), inertia.y(), inertia.z()));
      body->SetPosition(to_wm(b.position));
      body->SetLinearVelocity(to_wm(b.velocity));
      const Quat& q = b.orientation;
      body->SetQOrientation(Wm5::Quaterniond(q.w(), q.x(), q.y(), q.z()));
      body->SetAngularVelocity(to_wm(b.angular_velocity));
      body->mForce = force_at_stage;
      body->mTorque = torque_at_stage;
      ForceContext c;
      c.gravity = scene.world.gravity;
      c.rate = scene.world.damping_rate;
      c.angular_rate = scene.world.angular_damping_rate;
      c.scale = static_cast<double>(static_cast<float>(b.mass)) / b.mass;
      c.springs = springs[i];
      index_.push_back(i);
      bodies_.push_back(std::move(body));
      contexts_.push_back(std::move(c));
    }
    total_ = scene.bodies.size();
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t k = 0; k < bodies_.size(); ++k) contexts_[k].force = forces[index_[k]];
  }

  void set_torques(std::span<const Vec3> torques) override {
    for (std::size_t k = 0; k < bodies_.size(); ++k) contexts_[k].torque = torques[index_[k]];
  }

  void step() override {
    const double t = static_cast<double>(steps_) * h_;
    for (std::size_t k = 0; k < bodies_.size(); ++k) {
      ForceContext& c = contexts_[k];
      c.start = {from_wm(bodies_[k]->x()), from_wm(bodies_[k]->v())};
      t_current = &c;
      bodies_[k]->Update(t, h_);
      c.force.setZero();  // this step only (Engine::set_forces, set_torques)
      c.torque.setZero();
    }
    t_current = nullptr;
    ++steps_;
  }

  // Seconds of `steps` calls of step() (bare_step_loop in adapters.hpp). Wild Magic has no world
  // step: step() is Update on every body with the callbacks' context set (the step-start state the
  // springs are measured from), which a spring needs, so the bare loop is step() itself.
  double bare_seconds(std::int64_t steps) {
    const auto start = std::chrono::steady_clock::now();
    for (std::int64_t n = 0; n < steps; ++n) step();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  void read(std::span<BodyState> out) const override {
    (void)write(StateWriter<false>(out.data()));  // the finite check is read_append's business
  }

  // Each state written once from Wild Magic's own numbers and checked in the same pass.
  bool read_append(std::size_t, StateBuffer& out, StateUse use) const override {
    return append_states(out, total_, use, [this](auto w) { return write(w); });
  }

  void read_rotation(std::span<RotationState> out) const override {
    std::size_t k = 0, s = 0;
    for (std::size_t i = 0; i < total_; ++i) {
      if (s < statics_.size() && statics_[s].index == i) {
        out[i] = {statics_[s++].orientation, Vec3::Zero()};
        continue;
      }
      const Wm5::Quaterniond& q = bodies_[k]->q();
      out[i] = {Quat(q.W(), q.X(), q.Y(), q.Z()), from_wm(bodies_[k]->w())};
      ++k;
    }
  }

 private:
  // Puts every body's state in scene order into `w`; true when all are finite.
  template <typename Writer>
  bool write(Writer&& w) const {
    std::size_t k = 0, s = 0;
    for (std::size_t i = 0; i < total_; ++i) {
      if (s < statics_.size() && statics_[s].index == i) {
        const Vec3& p = statics_[s++].position;
        w.put(p.x(), p.y(), p.z(), 0.0, 0.0, 0.0);
        continue;
      }
      const WmVec &x = bodies_[k]->x(), &v = bodies_[k]->v();
      ++k;
      w.put(x.X(), x.Y(), x.Z(), v.X(), v.Y(), v.Z());
    }
    return w.finish();
  }

  double h_ = 1.0 / 60.0;
  std::int64_t steps_ = 0;
  std::size_t total_ = 0;
  std::vector<std::unique_ptr<WmBody>> bodies_;  // the dynamic bodies, in scene order
  std::vector<ForceContext> contexts_;           // one per entry of bodies_
  std::vector<std::size_t> index_;               // scene index of each entry of bodies_
  struct Static {
    std::size_t index;  // in Scene::bodies
    Vec3 position;
    Quat orientation;
  };
  std::vector<Static> statics_;  // in scene order
};

}  // namespace

std::unique_ptr<Engine> make_wildmagic() {
  return std::make_unique<WildMagicEngine>();
}

double bare_seconds_wildmagic(const Scene& scene, double h) {
  WildMagicEngine e;
  e.load(scene, h);
  return e.bare_seconds(step_count(scene, h));
}

}  // namespace dropcheck
