// Adapter for ODE (Open Dynamics Engine), Debian's double-precision build.
//
// Mapping (scene -> ODE), docs/engines.md sections 2, 3 and 5:
//   gravity g           -> dWorldSetGravity (ODE's default is zero).
//   damping rate k      -> per body dBodySetLinearDamping(s = 1 - exp(-k*h)): ODE scales v by
//                          (1 - s) once per step, so s is per step and depends on h. ODE's
//                          1 - s is phi to 1.1e-16 absolute: fine at any k*h (beyond k*h = 37
//                          it zeroes v where the law keeps less than 1e-16 of it).
//                          dBodySetLinearDampingThreshold(b, 0): the default skips damping while
//                          |v| <= 0.01 m/s. Angular damping k_a the same way (1 - exp(-k_a*h),
//                          threshold 0). Set per body: world defaults are copied only into bodies
//                          created after them.
//   law                 -> DampingOrder::AfterPosition: dxStepBody does v += h*(m*g + F)/m,
//                          x += h*v, then damps v.
//   mass m, inertia     -> dMassSetParameters(m, centre 0, the scene's principal moments),
//                          dBodySetMass (by default the moments of a uniform box:
//                          dMassSetBoxTotal's own formula up to rounding).
//   rotation            -> dBodySetQuaternion, dBodySetAngularVel (world frame), dBodyAddTorque
//                          (world frame) before dWorldStep; read with dBodyGetQuaternion and
//                          dBodyGetAngularVel. Law (ode/src/step.cpp, util.cpp, 0.16.2): the
//                          gyroscopic flag is on by default (dBodyCreate) and step.cpp codes it
//                          linearly implicit, w = (I_w - h*S(L))^-1*L (Lacoursiere; the explicit
//                          -w x I*w is compiled out); then dxStepBody's first-order quaternion
//                          update q += h/2*(0, w)*q, dNormalize4, and the angular damping last:
//                          linearly-implicit/first-order, AfterPosition like the linear damping.
//   static body         -> no ODE body: with contacts a box geom attached to body 0 (the static
//                          environment), without contacts nothing at all. Read back as its fixed
//                          position and zero velocity.
//   position, velocity  -> dBodySetPosition, dBodySetLinearVel; read with dBodyGetPosition and
//                          dBodyGetLinearVel (ODE has no interpolated state).
//   force this step     -> dBodyAddForce before dWorldStep; the step clears ODE's accumulator.
//   one step            -> dWorldStep(world, h). Chosen over dWorldQuickStep: identical for free
//                          bodies, and its direct (Dantzig LCP) solver rests a box 2e-11 m deep
//                          instead of 2e-8 (docs/engines.md section 5).
//   sleeping            -> dWorldSetAutoDisableFlag(0) and dBodySetAutoDisableFlag(b, 0) (off by
//                          default; set explicitly).
// Contacts (scene.world.contacts):
//   true  -> a dSimpleSpace with a dCreateBox geom per body; the near callback asks dCollide for up
//            to 8 contacts per pair (a box face needs >= 4) and makes a contact joint for each with
//            dContact zeroed, mode dContactApprox1 (mu is a coefficient, not a force bound),
//            mu = 0.5 for every pair (no mixing: the callback sets the pair's value), bounce 0;
//            a scene's friction (one per scene, docs/contact.md) replaces mu. Friction
//            directions: ODE's own (dPlaneSpace of the normal: x and z on a y-up floor), each
//            bounded by mu*N alone with dContactApprox1: the box pyramid
//            (FrictionModel::box_pyramid; slide_diagonal stops at step 44). A scene's
//            restitution e sets dContactBounce with bounce = e and bounce_vel = 0 (no
//            threshold); unset, bounce is 0. A sphere is a dCreateSphere geom of its radius.
//            ODE's bounce (contact.cpp, dxJointContact::getInfo2, read in ODE's sources): the
//            normal row's right-hand side is the push-out min(ERP*depth/h, max correcting vel),
//            raised to e*(-v_n) when the approach speed -v_n, taken from the velocity at the
//            start of the step (before this step's gravity), exceeds bounce_vel; the solver
//            leaves the normal velocity at that target. So the rebound leaves at e times the
//            speed of the step before contact, from where the body penetrated (EngineInfo::
//            bounce_law below, docs/contact.md).
//            World ERP 0.2 and CFM 1e-10 (ODE's double defaults), surface layer 0.
//            dWorldSetContactMaxCorrectingVel 0.3 m/s: ODE pushes a penetrating body out with the
//            velocity ERP*depth/h, capped by this value, and that velocity stays in the body.
//            Uncapped, a deep first contact pops the cube up (15 cm, docs/engines.md section 5); a
//            cap above about 2*g*h/ERP (0.41 m/s at 1/240) lets the body fly on after the push
//            (1 m/s rebounded 9 mm at 1/120 and 2.3 cm at 1/240). 0.3 m/s: no rebound from 1/30
//            to 1/240, and the 0.22 m first penetration of the undamped 10 m drop at 1/60 is
//            recovered in 0.7 s (ode_test.cpp).
//   false -> no space, no geoms, no contact joints.
// Errors: ODE reports through dError / dDebug (fatal: ODE exits or aborts when the handler returns)
// and dMessage (a warning). Our handlers throw EngineError from the fatal two; ODE is C++ built
// with unwind tables, so the throw unwinds through its frames to the adapter (ode_test.cpp shows
// it). The throw skips ODE's va_end (a no-op on the x86-64 and AArch64 ABIs). An error thrown out
// of dWorldStep or dSpaceCollide may leave that world's internals mid-update (a locked space, a
// step arena in use); such a world is marked poisoned, refuses further steps, and is leaked rather
// than destroyed, because destroying it can re-enter ODE's checks during unwinding.
#include <ode/ode.h>

#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <exception>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "adapters.hpp"
#include "harness/core/engine_writer.hpp"

namespace dropcheck {
namespace {

constexpr int kMaxContacts = 8;           // per geom pair; a resting box face needs >= 4
constexpr dReal kFriction = 0.5;          // Coulomb mu, dContactApprox1
constexpr dReal kMaxCorrectingVel = 0.3;  // m/s, depth recovery speed of a contact

#ifdef dDOUBLE
constexpr const char* kPrecisionToken = "ODE_double_precision";
#else
constexpr const char* kPrecisionToken = "ODE_single_precision";
#endif

// The last non-fatal ODE message on this thread, quoted in the next error as its context.
thread_local std::string t_last_message;

std::string format_ode(const char* kind, int num, const char* msg, va_list ap) {
  char text[512];
  std::vsnprintf(text, sizeof text, msg, ap);
  return std::string(kind) + " " + std::to_string(num) + ": " + text;
}

[[noreturn]] void throw_ode(const char* kind, int num, const char* msg, va_list ap) {
  std::string what = format_ode(kind, num, msg, ap);
  if (!t_last_message.empty()) what += " (after " + t_last_message + ")";
  t_last_message.clear();
  throw EngineError(what);
}

// dError: ODE calls exit(1) if this returns.
void on_ode_error(int num, const char* msg, va_list ap) {
  throw_ode("ODE error", num, msg, ap);
}

// dDebug (failed dIASSERT / dUASSERT / dAASSERT): ODE calls abort() if this returns.
void on_ode_debug(int num, const char* msg, va_list ap) {
  throw_ode("ODE internal error", num, msg, ap);
}

// dMessage: a warning (e.g. "LCP internal error, s <= 0"); printed as ODE would, and kept.
void on_ode_message(int num, const char* msg, va_list ap) {
  t_last_message = format_ode("ODE message", num, msg, ap);
  // Printed without the pivot's value ("(s=-0.0000e+00)"), so that one failure is one counted line
  // (Trajectory::messages); the error that may follow quotes it whole.
  const std::string line = t_last_message.substr(0, t_last_message.find(" (s="));
  std::cerr << line << '\n';
}

struct OdeLibrary {
  OdeLibrary() {
    dSetErrorHandler(on_ode_error);
    dSetDebugHandler(on_ode_debug);
    dSetMessageHandler(on_ode_message);
    ok = dInitODE2(0) != 0;
  }
  ~OdeLibrary() {
    if (ok) dCloseODE();
  }
  bool ok = false;
};

// Initialises ODE once per process (handlers first) and its per-thread data for this thread.
void ensure_ode() {
  static OdeLibrary library;
  t_last_message.clear();  // a warning from an earlier scene is no context for this one
  if (!library.ok) throw EngineError("ODE: dInitODE2 failed");
  // Same precision as our headers assume (dReal), or every state we read is garbage.
  if (!dCheckConfiguration(kPrecisionToken))
    throw EngineError(std::string("ODE: the library is not built with ") + kPrecisionToken);
  if (!dAllocateODEDataForThread(dAllocateMaskAll)) throw EngineError("ODE: no per-thread data");
}

// One loaded scene. Destroyed in ODE's order: contact group, space (and its geoms), world (and its
// bodies and joints). A poisoned world (an error escaped a step) is leaked on purpose (see top).
struct OdeWorld {
  dWorldID world = nullptr;
  dSpaceID space = nullptr;            // contacts only
  dJointGroupID contacts = nullptr;    // contacts only
  std::vector<dBodyID> bodies;         // indexed like Scene::bodies; nullptr when static
  std::vector<Vec3> static_positions;  // indexed like Scene::bodies
  dReal friction = kFriction;          // mu of every contact
  dReal bounce = 0;                    // restitution of every contact (0: dContactBounce off)
  std::exception_ptr callback_error;   // thrown in the near callback, rethrown after collide
  bool poisoned = false;

  ~OdeWorld() {
    if (poisoned) return;
    if (contacts) dJointGroupDestroy(contacts);
    if (space) dSpaceDestroy(space);
    if (world) dWorldDestroy(world);
  }
};

// A pair of geoms whose boxes may touch: one contact joint per contact point (mapping at the top).
void make_contacts(OdeWorld& w, dGeomID a, dGeomID b) {
  const dBodyID ba = dGeomGetBody(a);
  const dBodyID bb = dGeomGetBody(b);
  if (!ba && !bb) return;  // two static boxes
  dContact c[kMaxContacts] = {};
  const int n = dCollide(a, b, kMaxContacts, &c[0].geom, sizeof(dContact));
  for (int i = 0; i < n; ++i) {
    c[i].surface.mode = dContactApprox1 | (w.bounce > 0 ? dContactBounce : 0);
    c[i].surface.mu = w.friction;
    c[i].surface.bounce = w.bounce;
    c[i].surface.bounce_vel = 0;
    dJointAttach(dJointCreateContact(w.world, w.contacts, &c[i]), ba, bb);
  }
}

// dSpaceCollide's callback. No exception may leave it: the space stays locked if one does.
void near_callback(void* data, dGeomID a, dGeomID b) {
  auto& w = *static_cast<OdeWorld*>(data);
  if (w.callback_error) return;
  try {
    make_contacts(w, a, b);
  } catch (...) {
    w.callback_error = std::current_exception();
  }
}

class OdeEngine final : public Engine {
 public:
  EngineInfo info() const override {
    EngineInfo i;
    i.name = "ode";
    i.version = DROPCHECK_ODE_VERSION;
#ifdef dDOUBLE
    i.scalar = Scalar::f64;
#else
    i.scalar = Scalar::f32;
#endif
    i.capabilities = {.contacts = true,
                      .planar_only = false,
                      .rotation = Rotation::full,
                      .friction = true,
                      .restitution = true,
                      .spheres = true};
    i.law = DampingOrder::AfterPosition;
    i.friction_model = FrictionModel::box_pyramid;
    // Its bounce (mapping above): restitution of the step-start approach (bounce_vel 0), the
    // push-out of world ERP 0.2 capped at kMaxCorrectingVel. Measured on the bounces at e = 0.1,
    // 0.5, 0.9: within 1.0e-9, 2.0e-8 and 7.1e-8 m of this law over 3 s (ode_test.cpp).
    // Read in ODE's ode/src/lcp.cpp (dSolveLCP): when a pivot's step length s is not positive the
    // solver stops ("if we just keep going then we're going to get stuck in an infinite loop"),
    // zeroes x and w of the rows it has not reached and returns what it has.
    i.known_messages = {
        {"ODE message 3: LCP internal error, s <= 0",
         "ODE's LCP solver (lcp.cpp dSolveLCP) met a pivot step s <= 0, stopped and "
         "left zero impulse on the rows it had not reached: that step's contacts "
         "are not its law's"}};
    i.bounce_law = {.erp = 0.2, .max_push = kMaxCorrectingVel, .threshold = 0.0};
    i.rotation_law = {Gyroscopic::linearly_implicit, OrientationUpdate::first_order};
    i.damping_mapping =
        "dBodySetLinearDamping(s = 1 - exp(-k*h)), dBodySetAngularDamping(1 - exp(-k_a*h)), "
        "thresholds 0";
    i.contact_settings =
        "dWorldStep; box and sphere geoms, <= 8 contacts per pair, dContactApprox1, mu 0.5 or "
        "the scene's friction, bounce 0 or the scene's restitution (bounce_vel 0), "
        "ERP 0.2, CFM 1e-10, surface layer 0, max correcting vel 0.3 m/s";
    // Measured on drop_on_floor(_undamped): final y - 0.5 = -2.04e-11 m at 1/60 (proportional to
    // h: -5.1e-12 m at 1/240), -9.8e-10 m at 1/30 where it is still settling (ode_test.cpp). That
    // is the sink of its stack law below (CFM/ERP*h*m*g/4 = 2.04e-11 m for 1 kg at 1/60), so the
    // surface itself rests at the geometry.
    i.rest_offset = 0.0;
    i.rest_tolerance = 1e-8;
    // A stack: dWorldStep solves its LCP exactly; CFM/h on the diagonal against ERP*depth/h^2 on
    // the right (joints/contact.cpp getInfo2: rhs ERP*depth/h; step.cpp scales rhs and cfm by 1/h)
    // leaves each of the 4 contact points under a box face CFM/ERP*h*f deep. Measured on
    // stack_rest and mass_ratio at 1/60 and 1/240: 1.000 of it (4.083e-6 m under 1e5 kg at 1/60).
    i.stack_law = {.compliance = 1e-10 / 0.2, .points = 4, .sink_bound = 1e-12};
    // dWorldStep collides the geoms where they are at the end of the step (dSpaceCollide): ODE has
    // no continuous collision.
    i.continuous_collision = false;
    return i;
  }

  void load(const Scene& scene, double h) override {
    ensure_ode();
    w_.reset();
    w_ = std::make_unique<OdeWorld>();
    h_ = dReal(h);
    make_world(scene);
    const dReal phi = dReal(decay_per_step(scene, h));
    const dReal phi_a = dReal(angular_decay_per_step(scene, h));
    for (const Body& b : scene.bodies) add_body(scene, b, phi, phi_a);
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t i = 0; i < w_->bodies.size(); ++i) {
      if (w_->bodies[i]) dBodyAddForce(w_->bodies[i], forces[i].x(), forces[i].y(), forces[i].z());
    }
  }

  void set_torques(std::span<const Vec3> torques) override {
    for (std::size_t i = 0; i < w_->bodies.size(); ++i) {
      if (w_->bodies[i])
        dBodyAddTorque(w_->bodies[i], torques[i].x(), torques[i].y(), torques[i].z());
    }
  }

  void step() override {
    if (w_->poisoned) throw EngineError("ODE: world unusable after an earlier error");
    if (w_->space) collide();
    int stepped = 0;
    guarded([&] { stepped = dWorldStep(w_->world, h_); });
    if (w_->contacts) dJointGroupEmpty(w_->contacts);
    if (!stepped) throw EngineError("ODE: dWorldStep failed (out of step memory)");
  }

  // Seconds of `steps` ODE steps (dSpaceCollide with contacts, dWorldStep, dJointGroupEmpty)
  // without the adapter's checks (bare_step_loop in adapters.hpp).
  double bare_seconds(std::int64_t steps) {
    const auto start = std::chrono::steady_clock::now();
    for (std::int64_t n = 0; n < steps; ++n) {
      if (w_->space) dSpaceCollide(w_->space, w_.get(), near_callback);
      dWorldStep(w_->world, h_);
      if (w_->contacts) dJointGroupEmpty(w_->contacts);
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  void read(std::span<BodyState> out) const override {
    (void)write(StateWriter<false>(out.data()));  // the finite check is read_append's business
  }

  // Each state written once from ODE's own numbers and checked in the same pass (StateWriter).
  bool read_append(std::size_t, StateBuffer& out, StateUse use) const override {
    return append_states(out, w_->bodies.size(), use, [this](auto w) { return write(w); });
  }

  void read_rotation(std::span<RotationState> out) const override {
    (void)turn(RotationWriter<false>(out.data()));  // the check is read_rotation_append's
  }

  bool read_rotation_append(std::size_t, RotationBuffer& out, StateUse use) const override {
    return append_rotations(out, w_->bodies.size(), use, [this](auto w) { return turn(w); });
  }

 private:
  // Puts every body's state in order into `w` (a static body: its fixed position, at rest); true
  // when all are finite.
  template <typename Writer>
  bool write(Writer&& w) const {
    for (std::size_t i = 0; i < w_->bodies.size(); ++i) {
      const dBodyID b = w_->bodies[i];
      if (!b) {
        const Vec3& x = w_->static_positions[i];
        w.put(x.x(), x.y(), x.z(), 0.0, 0.0, 0.0);
        continue;
      }
      const dReal* x = dBodyGetPosition(b);
      const dReal* v = dBodyGetLinearVel(b);
      w.put(x[0], x[1], x[2], v[0], v[1], v[2]);
    }
    return w.finish();
  }

  // Puts every body's rotational state in order into `w` (a static body: unturned, at rest);
  // true when all are sound. ODE's quaternion is (w, x, y, z).
  template <typename Writer>
  bool turn(Writer&& w) const {
    for (const dBodyID b : w_->bodies) {
      if (!b) {
        w.put(1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        continue;
      }
      const dReal* q = dBodyGetQuaternion(b);
      const dReal* a = dBodyGetAngularVel(b);
      w.put(q[0], q[1], q[2], q[3], a[0], a[1], a[2]);
    }
    return w.finish();
  }

  void make_world(const Scene& scene) {
    w_->world = dWorldCreate();
    const Vec3& g = scene.world.gravity;
    dWorldSetGravity(w_->world, g.x(), g.y(), g.z());
    dWorldSetAutoDisableFlag(w_->world, 0);
    if (!scene.world.contacts) return;
    w_->space = dSimpleSpaceCreate(nullptr);
    w_->contacts = dJointGroupCreate(0);
    dWorldSetContactSurfaceLayer(w_->world, 0);
    dWorldSetContactMaxCorrectingVel(w_->world, kMaxCorrectingVel);
    const Material m = scene_material(scene);
    if (m.friction) w_->friction = dReal(*m.friction);
    if (m.restitution) w_->bounce = dReal(*m.restitution);
  }

  // A box or sphere geom of the body's size in the space, attached to `body` (nullptr: static).
  void add_geom(const Body& b, dBodyID body) {
    const Vec3 side = 2.0 * b.half_extents;
    const dGeomID g = b.shape == Shape::sphere
                          ? dCreateSphere(w_->space, b.radius)
                          : dCreateBox(w_->space, side.x(), side.y(), side.z());
    if (body)
      dGeomSetBody(g, body);
    else
      dGeomSetPosition(g, b.position.x(), b.position.y(), b.position.z());
  }

  void add_body(const Scene& scene, const Body& b, dReal phi, dReal phi_a) {
    w_->static_positions.push_back(b.position);
    w_->bodies.push_back(b.is_static ? nullptr : make_body(b, phi, phi_a));
    if (scene.world.contacts) add_geom(b, w_->bodies.back());
  }

  dBodyID make_body(const Body& b, dReal phi, dReal phi_a) {
    // Owned by the world from here on (dWorldDestroy frees it), even if a call below throws.
    const dBodyID body = dBodyCreate(w_->world);
    dBodySetPosition(body, b.position.x(), b.position.y(), b.position.z());
    dBodySetLinearVel(body, b.velocity.x(), b.velocity.y(), b.velocity.z());
    const Quat& o = b.orientation;
    const dQuaternion q = {o.w(), o.x(), o.y(), o.z()};
    dBodySetQuaternion(body, q);
    dBodySetAngularVel(body, b.angular_velocity.x(), b.angular_velocity.y(),
                       b.angular_velocity.z());
    dMass m;
    const Vec3 I = inertia_of(b);
    dMassSetParameters(&m, b.mass, 0, 0, 0, I.x(), I.y(), I.z(), 0, 0, 0);
    dBodySetMass(body, &m);
    // ODE: v *= (1 - s) once per step; (1 - s) = phi = exp(-k*h)  =>  s = 1 - exp(-k*h).
    dBodySetLinearDamping(body, 1 - phi);
    dBodySetLinearDampingThreshold(body, 0);
    dBodySetAngularDamping(body, 1 - phi_a);
    dBodySetAngularDampingThreshold(body, 0);
    dBodySetAutoDisableFlag(body, 0);
    return body;
  }

  // Contact joints for this step (near_callback). An error caught in the callback is rethrown
  // here, after dSpaceCollide has unlocked the space: the world stays consistent and usable.
  void collide() {
    guarded([&] { dSpaceCollide(w_->space, w_.get(), near_callback); });
    if (!w_->callback_error) return;
    dJointGroupEmpty(w_->contacts);
    std::rethrow_exception(std::exchange(w_->callback_error, nullptr));
  }

  // Runs an ODE call that may stop midway (a throw out of ODE's internals): the world is then
  // poisoned (see the top of this file).
  template <typename F>
  void guarded(F&& call) {
    try {
      call();
    } catch (...) {
      w_->poisoned = true;
      throw;
    }
  }

  dReal h_ = dReal(1.0 / 60.0);
  std::unique_ptr<OdeWorld> w_;
};

}  // namespace

std::unique_ptr<Engine> make_ode() {
  return std::make_unique<OdeEngine>();
}

double bare_seconds_ode(const Scene& scene, double h) {
  OdeEngine e;
  e.load(scene, h);
  return e.bare_seconds(step_count(scene, h));
}

}  // namespace dropcheck
