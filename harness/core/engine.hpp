// Engine: the one interface every physics engine is driven through. Adapters (adapters/*.cpp)
// implement it; they only convert data between a Scene and one engine.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <new>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "harness/core/bounce_law.hpp"
#include "harness/core/contact_solver.hpp"
#include "harness/core/friction_model.hpp"
#include "harness/core/law.hpp"
#include "harness/core/relative_cfm.hpp"
#include "harness/core/rotation_law.hpp"
#include "harness/core/scene.hpp"
#include "harness/core/stack_law.hpp"
#include "harness/core/turned_contact.hpp"

namespace dropcheck {

enum class Scalar { f32, f64 };

// Machine epsilon of the scalar: the spacing of numbers in [1, 2).
constexpr double machine_epsilon(Scalar s) {
  return s == Scalar::f32 ? 0x1p-23 : 0x1p-52;
}

// Which rotations an engine's adapter carries out (and reads back with Engine::read_rotation).
enum class Rotation {
  none,    // bodies never turn: a scene that needs rotation is not run
  spin_z,  // 2-D engine: turning about z only (orientation about z, angular velocity along z)
  full,    // 3-D rotation
};

struct Capabilities {
  bool contacts = false;     // can collide boxes with a static floor
  bool planar_only = false;  // 2-D engine: runs x-y plane scenes only
  Rotation rotation = Rotation::none;
  bool friction = false;     // maps the scene's friction (docs/contact.md)
  bool restitution = false;  // maps the scene's restitution
  bool spheres = false;      // collides spheres as well as boxes
};

// "free flight, contacts, 3-D rotation", "free flight, 2-D (x-y plane), turns about z", ...: what
// `dropcheck engines` and the report's engine table say an engine can run.
std::string to_string(const Capabilities& c);

// How an engine rounds one step of its law, so that the harness can repeat that step in the same
// arithmetic and operation order (harness/oracles/own_arithmetic.hpp). Declared by each adapter.
enum class DampingForm {
  other,         // not copied: the harness predicts the law in long double only
  phi_multiply,  // ours: v += g*h; v += (F/m)*h; v *= phi (phi = exp(-k*h) rounded to the scalar)
  pade,          // Box2D 2.4: v += (h*(1/m))*(m*g + F); v *= 1/(1 + h*c), c = expm1(k*h)/h rounded
  per_second_power,  // Bullet: v *= (1 - d)^h with d = 1 - exp(-k) rounded (its digits lost in
                     // 1 - d are copied; the rest of its order is not: per-step ulps tolerance)
};

struct EngineInfo {
  std::string name;     // registry name: ours, ours-f64, bullet, ode, box2d, mujoco
  std::string version;  // the engine library's version
  Scalar scalar = Scalar::f64;
  Capabilities capabilities;
  Law law;  // its member of the discrete-law family (harness/core/law.hpp)
  // The relative accuracy an error-controlled engine (law.scheme == Scheme::ErrorControlled) is
  // asked for, as its integrator takes it; 0 for a fixed-step engine.
  double accuracy = 0.0;
  // Its rotational member (harness/core/rotation_law.hpp), when capabilities.rotation is not none;
  // the angular damping sits where law.damping puts the linear one.
  RotationLaw rotation_law;
  DampingForm arithmetic = DampingForm::other;  // its operation order, when the harness copies it
  std::string damping_mapping;   // how k becomes the engine's parameter, e.g. "d = 1 - exp(-k)"
  std::string contact_settings;  // contact model and parameters used when contacts = true
  // What lines the engine prints mean, read in its source: a line that starts with `starts` means
  // `meaning` (the report and a departing contact verdict quote it beside the count).
  struct KnownMessage {
    std::string starts, meaning;
  };
  std::vector<KnownMessage> known_messages;
  // How its contact solver bounds friction (docs/contact.md), for an engine that maps materials.
  FrictionModel friction_model = FrictionModel::cone;
  // How its contact solver reaches a step's impulses (harness/core/contact_solver.hpp): exactly,
  // or by a fixed number of iterations the harness replays.
  ContactSolver contact_solver;
  // How its contact turns a falling body around (harness/core/bounce_law.hpp), for an engine that
  // maps restitution.
  BounceLaw bounce_law = kIdealBounce;
  // How its contacts hold a resting stack of boxes (harness/core/stack_law.hpp).
  StackLaw stack_law;
  // Constraint force mixing relative to each diagonal entry of its contact LCP, with its error
  // reduction (harness/core/relative_cfm.hpp): what its slide law and sink follow. None: rigid.
  RelativeCfm relative_cfm;
  // Where its contact acts on a turned or turning box (harness/core/turned_contact.hpp).
  TurnedContact turned_contact = TurnedContact::not_declared;
  // Landing on a static floor: where the centre of a resting box sits relative to the geometric
  // rest height (floor top + half extent), in m, and how far from that still counts as expected.
  // Documented per engine in docs/engines.md section 5 (Box2D: +0.015 from skin and slop).
  double rest_offset = 0.0;
  double rest_tolerance = 1e-3;
  // Contacts as the adapter configures them: true when a fast body is swept between step ends
  // (continuous collision) against a static floor; false when overlap is tested only at step ends,
  // so a body that jumps over the floor in one step tunnels (a named limit, docs/engines.md 5).
  bool continuous_collision = false;
  // True for an engine that runs in a process of its own (an external engine, adapters/exec.cpp):
  // the runner does not fork for it (its crash cannot end dropcheck, and as dropcheck's own child
  // its death is read truly: "crashed: SIGSEGV"), and checks the run's wall-clock limit per step.
  bool own_process = false;
};

struct BodyState {
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
};

// The rotational state of one body, recorded beside its BodyState for a scene that needs rotation
// (Trajectory::rotations): kept apart so that a run without rotation moves no extra byte.
struct RotationState {
  Quat orientation = Quat::Identity();   // unit quaternion, body frame to world frame
  Vec3 angular_velocity = Vec3::Zero();  // rad/s, world frame
};

// The capability (the protocol's word, docs/protocol.md) whose absence makes Engine::cannot_run
// refuse with `refusal` ("contacts" for "no contacts"), or empty when none lifts it (a 3-D scene
// on a 2-D engine, an adapter's own limit).
std::string capability_lifting(const std::string& refusal);

// A 2-D engine's turn: the angle a about z as q = (cos(a/2), 0, 0, sin(a/2)), w = (0, 0, w_z).
RotationState turn_about_z(double angle, double w_z);

// Storage for states (UnwrittenAllocator): 64-byte aligned (whole cache lines); for a block of 4
// MiB or more, the whole 2 MiB pages inside it are advised as transparent huge pages (madvise
// MADV_HUGEPAGE, malloc's placement kept), so that a long trajectory takes one page fault per 2 MiB
// instead of one per 4 KiB written (engine.cpp).
void* allocate_states(std::size_t bytes);
// Frees what allocate_states(bytes) gave.
void free_states(void* p, std::size_t bytes) noexcept;

// Allocator of state storage: a state added without a value (resize(n), emplace_back()) is left
// unwritten, for the caller to write at once, so the runner's states are written once instead of
// zeroed first and then written (a second pass of stores over fresh memory). Blocks come from
// allocate_states. Otherwise as std::allocator.
template <typename T>
struct UnwrittenAllocator {
  using value_type = T;

  UnwrittenAllocator() = default;
  template <typename U>
  UnwrittenAllocator(const UnwrittenAllocator<U>&) noexcept {}  // NOLINT: rebinding converts

  T* allocate(std::size_t n) {
    if (n > SIZE_MAX / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocate_states(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { free_states(p, n * sizeof(T)); }
  // Leaves the object unwritten: BodyState is an aggregate (an implicit-lifetime type, created by
  // the allocation); its default member initialisers are skipped on purpose.
  template <typename U>
  void construct(U*) noexcept {}
  // Any other construction as std::allocator does it.
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  // Every instance can free what another allocated.
  template <typename U>
  bool operator==(const UnwrittenAllocator<U>&) const noexcept {
    return true;
  }
};

// States in body-major runs (Trajectory::states): resize() and emplace_back() without a value leave
// the new states unwritten (UnwrittenAllocator); write them before anything reads them.
using StateBuffer = std::vector<BodyState, UnwrittenAllocator<BodyState>>;

// Rotational states, stored like StateBuffer (unwritten on resize, huge pages for long runs): a
// rotating run keeps one per body per sample, and a value-initialising vector would write every
// one twice.
using RotationBuffer = std::vector<RotationState, UnwrittenAllocator<RotationState>>;

// True when every number of every rotational state is finite (one branch-free pass).
bool all_finite(std::span<const RotationState> rotations);

// How far an orientation's norm may be from 1 and still be a unit quaternion: a float engine
// renormalises to within ~1e-7, with room; an engine that answers (0, 0, 0, 0) or an unnormalised
// q reports something that is no rotation. Compared as |q|^2 (no square root): (1 -+ 1e-4)^2.
inline constexpr double kUnitSlack = 1e-4;
inline constexpr double kUnitNorm2Min = (1 - kUnitSlack) * (1 - kUnitSlack);
inline constexpr double kUnitNorm2Max = (1 + kUnitSlack) * (1 + kUnitSlack);

// True when every number of every rotational state is finite and every orientation is a unit
// quaternion (one pass): what a run needs of each step's rotations.
bool rotations_sound(std::span<const RotationState> rotations);

// What the states an Engine::read_append adds are for.
enum class StateUse {
  next_step,  // read again soon (the next step's forces or checks): keep them in the cache
  kept,       // kept for after the run only: they may be written around the cache (streamed)
};

// True when every number of every state is finite (one branch-free pass, engine.cpp).
bool all_finite(std::span<const BodyState> states);

class Engine {
 public:
  virtual ~Engine() = default;

  virtual EngineInfo info() const = 0;

  // Why this engine cannot run `scene` ("not planar", "no contacts"); empty when it can.
  virtual std::string cannot_run(const Scene& scene) const;

  // Builds the engine's world for `scene`, to be stepped at exactly h seconds per step.
  virtual void load(const Scene& scene, double h) = 0;

  // Asks an error-controlled engine for relative accuracy `a` (> 0) from the next load() on
  // (info().accuracy then says `a`). A fixed-step engine returns false and changes nothing.
  virtual bool set_accuracy(double /*a*/) { return false; }

  // The steps an error-controlled engine has taken of its own since load() (it may take several
  // per step of h); 0 for a fixed-step engine.
  virtual std::int64_t engine_steps() const { return 0; }

  // For `identify --combine` only: from the next load() on, pass each body's own friction
  // coefficient to the engine verbatim, so that the engine's combine rule, not the adapter's
  // mapping, makes each pair's value (harness/oracles/identify_friction.hpp). False when the
  // adapter cannot: the engine has no per-body material (ODE's near callback sets each pair).
  virtual bool use_body_materials() { return false; }

  // This step's external force on each body (N), indexed like Scene::bodies; applied once, by the
  // next step() only. Entries of static bodies are zero and ignored.
  virtual void set_forces(std::span<const Vec3> forces) = 0;

  // This step's external torque on each body (N m, world frame), like set_forces. Called only for
  // a scene with torques, on an engine with rotation; the default throws EngineError.
  virtual void set_torques(std::span<const Vec3> torques);

  // Advances exactly one step of h. Throws EngineError when the engine reports an error.
  virtual void step() = 0;

  // The true state of every body after the last step (not an interpolated or stale copy).
  virtual void read(std::span<BodyState> out) const = 0;

  // Appends what read() gives for the scene's `bodies` bodies to the end of `out` and returns true
  // when every number of them is finite: how the runner reads each step. The default appends
  // unwritten states (StateBuffer), read()s into them and checks them in a second pass
  // (all_finite); an adapter may instead write them from its own arrays and check them in the same
  // pass, streamed past the cache when `use` is kept (StateWriter, harness/core/engine_writer.hpp).
  virtual bool read_append(std::size_t bodies, StateBuffer& out, StateUse use) const;

  // The true orientation and world-frame angular velocity of every body after the last step, for
  // an engine whose capabilities include rotation (the runner calls it only for a scene that needs
  // rotation). The default throws EngineError: an engine without rotation is never asked.
  virtual void read_rotation(std::span<RotationState> out) const;

  // Appends what read_rotation() gives for the scene's `bodies` bodies to the end of `out` and
  // returns rotations_sound() of them: how the runner reads each step of a rotating run. The
  // default read_rotation()s into unwritten states and checks them in a second pass; an adapter
  // may write them from its own arrays and check them in the same pass, streamed past the cache
  // when `use` is kept (RotationWriter, harness/core/engine_writer.hpp).
  virtual bool read_rotation_append(std::size_t bodies, RotationBuffer& out, StateUse use) const;

  // True when the last step clamped a body's speed or turn (Box2D moves at most 2 m and turns at
  // most pi/2 per step; Bullet turns at most pi/4 per step).
  virtual bool speed_clamped() const { return false; }
};

// An Engine that passes every call on to another: the base of wrappers that add one thing to a run
// (counting steps, a deadline, a test double's extra work) and override only the calls they add
// it to. read_append and read_rotation_append are passed on too, so the wrapped engine keeps its
// own fast reads: a wrapper that changes what read() or read_rotation() report overrides the
// matching *_append as well, with Engine's default (which reads through the wrapper's own read).
class ForwardingEngine : public Engine {
 public:
  explicit ForwardingEngine(Engine& inner) : inner_(inner) {}
  EngineInfo info() const override { return inner_.info(); }
  std::string cannot_run(const Scene& scene) const override { return inner_.cannot_run(scene); }
  void load(const Scene& scene, double h) override { inner_.load(scene, h); }
  bool set_accuracy(double a) override { return inner_.set_accuracy(a); }
  std::int64_t engine_steps() const override { return inner_.engine_steps(); }
  bool use_body_materials() override { return inner_.use_body_materials(); }
  void set_forces(std::span<const Vec3> forces) override { inner_.set_forces(forces); }
  void set_torques(std::span<const Vec3> torques) override { inner_.set_torques(torques); }
  void step() override { inner_.step(); }
  void read(std::span<BodyState> out) const override { inner_.read(out); }
  bool read_append(std::size_t bodies, StateBuffer& out, StateUse use) const override {
    return inner_.read_append(bodies, out, use);
  }
  void read_rotation(std::span<RotationState> out) const override { inner_.read_rotation(out); }
  bool read_rotation_append(std::size_t bodies, RotationBuffer& out, StateUse use) const override {
    return inner_.read_rotation_append(bodies, out, use);
  }
  bool speed_clamped() const override { return inner_.speed_clamped(); }

 protected:
  Engine& inner_;
};

// An engine refused or failed a call; a result to record, never a crash of the harness.
struct EngineError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An engine whose own process went away (an external engine that crashed or exited): the run ends
// as crashed, like a built-in engine whose isolated process died.
struct EngineDied : EngineError {
  using EngineError::EngineError;
};

// A run that passed its wall-clock limit (an engine in its own process, checked per step): the run
// ends as timed out.
struct RunTimeLimitExceeded : EngineError {
  using EngineError::EngineError;
};

// Makes a fresh engine; how engine-neutral code (timing, evaluation, checks) gets engines.
using EngineFactory = std::function<std::unique_ptr<Engine>()>;

const char* to_string(Scalar scalar);
// "phi multiply", "Pade 1/(1 + h*c)", "not copied".
const char* to_string(DampingForm form);
// "none", "about z", "3-D".
const char* to_string(Rotation rotation);

}  // namespace dropcheck
