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
// Contacts: not mapped (boxes against a floor with Chipmunk's 0.1 m default collision slop): a
// scene with contacts is not run.
// Debian builds Chipmunk with its debug checks on: the first cpSpaceNew of a process prints two
// lines to stdout ("Initializing cpSpace ... (Debug Enabled)", cpSpace.c), which would land inside
// dropcheck's own output (its tables on stdout). The adapter makes that first call once per process
// with stdout pointed at /dev/null (quiet_first_space); forked runs inherit the flag Chipmunk
// keeps. Errors: Chipmunk's hard assertions (a non-positive mass or moment, a non-finite state in a
// debug build) print and abort(); the isolated run reports that as a crash.
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

  Space() : space((quiet_first_space(), cpSpaceNew())) {}
  Space(const Space&) = delete;
  Space& operator=(const Space&) = delete;
  ~Space() {
    for (cpBody* b : bodies) {
      cpSpaceRemoveBody(space, b);
      cpBodyFree(b);
    }
    cpSpaceFree(space);
  }
};

class ChipmunkEngine final : public Engine {
 public:
  EngineInfo info() const override {
    EngineInfo i;
    i.name = "chipmunk";
    i.version = std::to_string(CP_VERSION_MAJOR) + "." + std::to_string(CP_VERSION_MINOR) + "." +
                std::to_string(CP_VERSION_RELEASE);
    i.scalar = sizeof(cpFloat) == sizeof(double) ? Scalar::f64 : Scalar::f32;
    i.capabilities = {.contacts = false, .planar_only = true, .rotation = Rotation::spin_z};
    i.law = Law{DampingOrder::BeforeForces, PositionUpdate::Explicit};
    i.rotation_law = {Gyroscopic::none, OrientationUpdate::exponential_map};
    i.damping_mapping =
        "cpSpaceSetDamping(exp(-k)) per second, one for v and w; v = v*exp(-k)^h + a*h";
    return i;
  }

  std::string cannot_run(const Scene& scene) const override {
    if (std::string why = Engine::cannot_run(scene); !why.empty()) return why;
    if (needs_rotation(scene) && moves_along_a_line(scene) &&
        scene.world.damping_rate != scene.world.angular_damping_rate)
      return "damping: Chipmunk damps v and w by one space damping, and this scene's k and k_a "
             "differ";
    return {};
  }

  void load(const Scene& scene, double h) override {
    if (!is_planar(scene)) throw EngineError("not planar");
    h_ = h;
    w_ = std::make_unique<Space>();
    cpSpaceSetGravity(w_->space, to_cp(scene.world.gravity));
    const bool linear = !needs_rotation(scene) || moves_along_a_line(scene);
    cpSpaceSetDamping(w_->space, std::exp(-(linear ? scene.world.damping_rate
                                                   : scene.world.angular_damping_rate)));
    cpSpaceSetSleepTimeThreshold(w_->space, INFINITY);
    for (const Body& b : scene.bodies) w_->bodies.push_back(add_body(b));
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
  // True when some body moves along a line: a start velocity, gravity, or a force.
  static bool moves_along_a_line(const Scene& scene) {
    if (!scene.world.gravity.isZero(0.0) || !scene.forces.empty()) return true;
    for (const Body& b : scene.bodies)
      if (!b.is_static && !b.velocity.isZero(0.0)) return true;
    return false;
  }

  cpBody* add_body(const Body& b) {
    cpBody* body = b.is_static ? cpBodyNewStatic() : cpBodyNew(b.mass, inertia_of(b).z());
    cpBodySetPosition(body, to_cp(b.position));
    if (!b.is_static) {
      cpBodySetVelocity(body, to_cp(b.velocity));
      const Quat& q = b.orientation;  // about z only (cannot_run)
      cpBodySetAngle(body, 2.0 * std::atan2(q.z(), q.w()));
      cpBodySetAngularVelocity(body, b.angular_velocity.z());
    }
    return cpSpaceAddBody(w_->space, body);
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
