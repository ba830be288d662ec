// Adapter for Chipmunk 7.0.3 (Chipmunk2D; Debian's build, cpFloat = double), 2-D. Planar scenes
// only: the x-y plane, y up; z is dropped.
//
// Mapping (scene -> Chipmunk), read in Chipmunk 7.0.3's src/cpSpaceStep.c, cpBody.c, cpSpace.c:
//   gravity g           -> cpSpaceSetGravity (x, y); Chipmunk's default is zero.
//   damping rate k      -> cpSpaceSetDamping(space, exp(-k)): the fraction of velocity a body
//                          keeps per second. cpSpaceStep raises it to the step, damping =
//                          cpfpow(space->damping, dt), so phi = exp(-k)^h = exp(-k*h) up to
//                          the rounding of exp(-k) (relative 1e-16 times h: below the rule's ulps).
//                          One value for every body and for both v and w (Chipmunk has no
//                          per-body or separate angular damping): exp(-k), or exp(-k_a) when
//                          nothing moves along a line (no start velocity, gravity or force); a
//                          scene that needs both with k != k_a is not run (cannot_run).
//   law                 -> DampingOrder::BeforeForces, PositionUpdate::Explicit: cpSpaceStep first
//                          moves every body (cpBodyUpdatePosition: p += h*v), then collides, then
//                          updates velocities (cpBodyUpdateVelocity: v = v*phi + (g + f/m)*h,
//                          f = 0): x_{n+1} = x_n + h*v_n; v_{n+1} = phi*v_n + h*a. The only shipped
//                          engine whose position moves with the step-start velocity.
//   mass m              -> cpBodyNew(m, I_z) with the scene's moment about z (inertia_of).
//   rotation (about z)  -> cpBodySetAngle(2*atan2(qz, qw)), cpBodySetAngularVelocity(w_z),
//                          cpBodySetTorque(tau_z) before the step; read back as
//                          q = (cos(a/2), 0, 0, sin(a/2)) from cpBodyGetAngle and w_z from
//                          cpBodyGetAngularVelocity. Law, as for the position:
//                          cpBodyUpdatePosition turns first, a += h*w (the exact turn by the
//                          step-start w: the exponential map), then cpBodyUpdateVelocity does
//                          w = w*D^h + t/I*h; no gyroscopic term (about a principal axis it is
//                          zero for every member): no-gyro/exp-map with the explicit update.
//   static body         -> cpBodyNewStatic at its position, added to the space (never moved).
//   position, velocity  -> cpBodySetPosition, cpBodySetVelocity; read with cpBodyGetPosition and
//                          cpBodyGetVelocity after the step (the centre of gravity is the body's
//                          origin: cpBodyNew leaves it at (0, 0)).
//   force this step     -> cpBodySetForce(F) before cpSpaceStep; cpBodyUpdateVelocity resets it.
//   sleeping            -> off: Chipmunk's default sleepTimeThreshold is INFINITY (cpSpaceInit),
//                          set explicitly.
//   one step            -> one cpSpaceStep(space, h) (10 solver iterations, Chipmunk's default;
//                          no effect on free bodies).
// Contacts (harness/core/chipmunk_world.hpp, built once for the adapter and its replay): a
// cpBoxShapeNew box per body (no radius) or a cpCircleShapeNew circle per sphere, friction sqrt(mu)
// and elasticity sqrt(e) per shape (Chipmunk multiplies the two: cpArbiterUpdate), 10 iterations,
// collision slop 0.005 m instead of the 0.1 meant for pixels. A resting box sits a slop into its
// floor. Its solver is judged by harness/oracles/chipmunk_step.hpp, a port of cpSpaceStep in
// Chipmunk's own arithmetic. Debian builds Chipmunk with its debug checks on: the first cpSpaceNew
// of a process prints two lines to stdout ("Initializing cpSpace ... (Debug Enabled)", cpSpace.c),
// which would land inside dropcheck's own output (its tables on stdout). The adapter makes that
// first call once per process with stdout pointed at /dev/null (quiet_first_space); forked runs
// inherit the flag Chipmunk keeps. Errors: Chipmunk's hard assertions (a non-positive mass or
// moment, a non-finite state in a debug build) print and abort(); the isolated run reports that as
// a crash.
#include <chipmunk/chipmunk.h>
#include <chipmunk/chipmunk_structs.h>
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "adapters.hpp"
#include "harness/core/chipmunk_world.hpp"
#include "harness/core/engine_writer.hpp"

namespace dropcheck {
namespace {

// Makes Chipmunk's first cpSpaceNew of this process with stdout pointed at /dev/null (see the top
// of this file). Best effort: if /dev/null cannot be opened, the banner is printed.
void quiet_first_space() {
  static const bool done = [] {
    std::fflush(stdout);
    const int saved = dup(STDOUT_FILENO);
    const int null = open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved >= 0 && null >= 0) dup2(null, STDOUT_FILENO);
    cpSpaceFree(cpSpaceNew());
    std::fflush(stdout);
    if (saved >= 0) {
      dup2(saved, STDOUT_FILENO);
      close(saved);
    }
    if (null >= 0) close(null);
    return true;
  }();
  (void)done;
}

cpVect to_cp(const Vec3& v) {
  return cpv(v.x(), v.y());
}

// Owns a cpSpace and its bodies (cpSpaceFree frees neither bodies nor shapes).
struct Space {
  cpSpace* space = nullptr;
  std::vector<cpBody*> bodies;  // indexed like Scene::bodies
  std::vector<cpShape*> shapes;

  Space() : space((quiet_first_space(), cpSpaceNew())) {}
  Space(const Space&) = delete;
  Space& operator=(const Space&) = delete;
  ~Space() {
    for (cpShape* s : shapes) {
      cpSpaceRemoveShape(space, s);
      cpShapeFree(s);
    }
    for (cpBody* b : bodies) {
      cpSpaceRemoveBody(space, b);
      cpBodyFree(b);
    }
    cpSpaceFree(space);
  }
};

// A resting box sinks until its overlap is the collision slop: the bias impulse pushes out only
// the overlap beyond it (cpArbiterPreStep). Measured on drop_on_floor(_undamped) at 1/60: -0.005 m.
constexpr double kRestOffset = -0.005;
constexpr double kRestTolerance = 1e-4;
// A stack that starts resting settles anywhere within the slop of each contact under it: Chipmunk
// pushes out only the overlap beyond the slop, so nothing lifts a body that creeps into it. The
// bound is the slop of stack_rest's two contacts under its top box, 2*0.005 m, from the rest
// offset either way. Measured on stack_rest at 1/60 after 5 s: medium 1.23e-3 m and small
// 2.49e-3 m into their floors (3.77e-3 and 7.51e-3 m above a slop per contact), drifting sideways
// 8.8e-4 and 1.6e-3 m (the bound 2e-3 m), still to 1e-16 m/s.
constexpr StackLaw kStackLaw = {
    .iterations = 10, .sink_bound = 2 * 0.005, .drift_bound = 2e-3, .still_bound = 1e-3};

class ChipmunkEngine final : public Engine {
 public:
  EngineInfo info() const override {
    EngineInfo i;
    i.name = "chipmunk";
    i.version = std::to_string(CP_VERSION_MAJOR) + "." + std::to_string(CP_VERSION_MINOR) + "." +
                std::to_string(CP_VERSION_RELEASE);
    i.scalar = sizeof(cpFloat) == sizeof(double) ? Scalar::f64 : Scalar::f32;
    i.capabilities = {.contacts = true,
                      .planar_only = true,
                      .rotation = Rotation::spin_z,
                      .friction = true,
                      .restitution = true,
                      .spheres = true};
    i.law = Law{DampingOrder::BeforeForces, PositionUpdate::Explicit};
    i.rotation_law = {Gyroscopic::none, OrientationUpdate::exponential_map};
    i.damping_mapping =
        "cpSpaceSetDamping(exp(-k)) per second, one for v and w; v = v*exp(-k)^h + a*h";
    const ChipmunkWorld defaults;
    i.contact_settings =
        "cpBoxShapeNew boxes (no radius) or cpCircleShapeNew circles, friction sqrt(mu) each "
        "(product: mu, 0.5 unset), elasticity sqrt(e) each (product: e, 0 unset), " +
        std::to_string(defaults.iterations) +
        " iterations, collision slop 0.005 m, bias and "
        "persistence Chipmunk's defaults";
    // Its contact solver, read in Chipmunk 7.0.3's src/cpSpaceStep.c (cpSpaceStep) and
    // src/cpArbiter.c (cpArbiterApplyImpulse: the bias, normal, then friction clamped by u*jn):
    // replayed by harness/oracles/chipmunk_step.hpp.
    i.contact_solver = {.kind = ContactSolverKind::chipmunk_7,
                        .velocity_iterations = defaults.iterations};
    i.rest_offset = kRestOffset;
    i.rest_tolerance = kRestTolerance;
    i.stack_law = kStackLaw;
    return i;
  }

  std::string cannot_run(const Scene& scene) const override {
    if (std::string why = Engine::cannot_run(scene); !why.empty()) return why;
    if (needs_rotation(scene) && chipmunk_moves_along_a_line(scene) &&
        scene.world.damping_rate != scene.world.angular_damping_rate)
      return "damping: Chipmunk damps v and w by one space damping, and this scene's k and k_a "
             "differ";
    return {};
  }

  void load(const Scene& scene, double h) override {
    if (!is_planar(scene)) throw EngineError("not planar");
    h_ = h;
    w_ = std::make_unique<Space>();
    const ChipmunkWorld world = chipmunk_world(scene, body_materials_);
    cpSpaceSetGravity(w_->space, cpv(world.gx, world.gy));
    cpSpaceSetDamping(w_->space, world.damping);
    cpSpaceSetSleepTimeThreshold(w_->space, INFINITY);
    cpSpaceSetIterations(w_->space, world.iterations);
    cpSpaceSetCollisionSlop(w_->space, world.collision_slop);
    // Chipmunk's own defaults, set from the world the replay reads, so that both use one value.
    cpSpaceSetCollisionBias(w_->space, world.collision_bias);
    cpSpaceSetCollisionPersistence(w_->space, world.collision_persistence);
    for (const ChipmunkBox& b : world.bodies) w_->bodies.push_back(add_body(b, world.contacts));
  }

  void set_forces(std::span<const Vec3> forces) override {
    for (std::size_t i = 0; i < w_->bodies.size(); ++i)
      if (cpBodyGetType(w_->bodies[i]) == CP_BODY_TYPE_DYNAMIC)
        cpBodySetForce(w_->bodies[i], to_cp(forces[i]));
  }

  void set_torques(std::span<const Vec3> torques) override {
    for (std::size_t i = 0; i < w_->bodies.size(); ++i)
      if (cpBodyGetType(w_->bodies[i]) == CP_BODY_TYPE_DYNAMIC)
        cpBodySetTorque(w_->bodies[i], torques[i].z());
  }

  void step() override { cpSpaceStep(w_->space, h_); }

  bool use_body_materials() override { return body_materials_ = true; }

  // Seconds of `steps` calls of cpSpaceStep alone (bare_step_loop in adapters.hpp).
  double bare_seconds(std::int64_t steps) {
    const auto start = std::chrono::steady_clock::now();
    for (std::int64_t n = 0; n < steps; ++n) cpSpaceStep(w_->space, h_);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  void read(std::span<BodyState> out) const override {
    (void)write(StateWriter<false>(out.data()));  // the finite check is read_append's business
  }

  // Each state written once from Chipmunk's own numbers and checked in the same pass.
  bool read_append(std::size_t, StateBuffer& out, StateUse use) const override {
    return append_states(out, w_->bodies.size(), use, [this](auto w) { return write(w); });
  }

  void read_rotation(std::span<RotationState> out) const override {
    for (std::size_t i = 0; i < w_->bodies.size(); ++i)
      out[i] = turn_about_z(cpBodyGetAngle(w_->bodies[i]), cpBodyGetAngularVelocity(w_->bodies[i]));
  }

 private:
  cpBody* add_body(const ChipmunkBox& b, bool contacts) {
    cpBody* body = b.is_static ? cpBodyNewStatic() : cpBodyNew(b.mass, b.moment);
    cpBodySetPosition(body, cpv(b.x, b.y));
    if (!b.is_static) {
      cpBodySetVelocity(body, cpv(b.vx, b.vy));
      cpBodySetAngle(body, b.angle);
      cpBodySetAngularVelocity(body, b.w);
    }
    cpSpaceAddBody(w_->space, body);
    if (contacts) {
      cpShape* shape = cpSpaceAddShape(
          w_->space, b.radius > 0.0 ? cpCircleShapeNew(body, b.radius, cpvzero)
                                    : cpBoxShapeNew(body, 2.0 * b.hx, 2.0 * b.hy, 0.0));
      cpShapeSetFriction(shape, b.friction);
      cpShapeSetElasticity(shape, b.elasticity);
      w_->shapes.push_back(shape);
    }
    return body;
  }

  // Puts every body's state in order into `w` (z = 0); true when all are finite. Read from the
  // body's own p and v (chipmunk_structs.h, one of Chipmunk's public headers): cpBodyGetPosition
  // rebuilds p from the body's transform, the same number for a centre of gravity at the origin
  // (p.x - (0*cos - 0*sin)), through a library call per number (6 ns of a 34 ns body-step at N =
  // 1000 with both calls, bench/loop_bench.cpp).
  template <typename Writer>
  bool write(Writer&& w) const {
    for (const cpBody* b : w_->bodies) w.put(b->p.x, b->p.y, 0.0, b->v.x, b->v.y, 0.0);
    return w.finish();
  }

  double h_ = 1.0 / 60.0;
  std::unique_ptr<Space> w_;
  bool body_materials_ = false;  // Engine::use_body_materials
};

}  // namespace

std::unique_ptr<Engine> make_chipmunk() {
  quiet_first_space();  // in the process that forks the runs
  return std::make_unique<ChipmunkEngine>();
}

double bare_seconds_chipmunk(const Scene& scene, double h) {
  ChipmunkEngine e;
  e.load(scene, h);
  return e.bare_seconds(step_count(scene, h));
}

}  // namespace dropcheck
