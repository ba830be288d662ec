// Adapter for MuJoCo 2.2.2 (double). The scene becomes an MJCF model built in memory (a virtual
// file, nothing on disk), loaded with mj_loadXML and stepped with mj_step.
//
// Mapping (scene -> MuJoCo):
//   step h, gravity g   -> <option timestep="h" gravity="gx gy gz" integrator="Euler"/>, both set
//                          explicitly (defaults: 0.002 s and (0, 0, -9.81)); the scene's axes are
//                          kept as they are (y up), gravity simply points along -y
//   damping rate k      -> <joint type="free" damping="b"/>, b = m*(exp(k*h) - 1)/h, then
//                          dof_damping of the 3 rotational dofs set to I_i*(exp(k_a*h) - 1)/h.
//                          mj_Euler integrates damping implicitly: v = (v + a*h)/(1 + h*b/m), and
//                          1/(1 + h*b/m) = exp(-k*h): the order of ours
//                          (DampingOrder::AfterForces); the same per rotational dof, whose mass is
//                          the moment I_i (the mass matrix of a free body is diagonal: m, m, m,
//                          Ixx, Iyy, Izz)
//   mass, inertia, shape-> <inertial mass="m" diaginertia="Ixx Iyy Izz"> (exactly m and the
//                          scene's moments; a geom-derived mass goes through density*volume) and a
//                          box geom of the half extents or a sphere geom of the radius
//   rotation            -> qpos[3..6] = (qw, qx, qy, qz); qvel[3..5] is the angular velocity in the
//                          BODY frame (engine_core_smooth.c: the free joint's rotational axes are
//                          the body's), written as R^T*w and read back as R*w_b. Torque: the
//                          world-frame torque of xfrc_applied (MuJoCo turns it into body axes with
//                          the step-start R; zeroed after each step, MuJoCo never clears it).
//                          Law: the Coriolis term of mj_rne at the step start (explicit), the
//                          quaternion by mju_quatIntegrate, q*exp(h*w_b/2) (the exponential map,
//                          engine_util_spatial.c): explicit/exp-map
//   static body         -> a box geom in the worldbody
//   contacts = false    -> contype="0" conaffinity="0" on every geom: no collision at all
//   position, velocity  -> qpos[0..2], qvel[0..2] of the free joint, written after mj_makeData and
//                          read after mj_step (xpos is one step stale after mj_step)
//   force this step     -> qfrc_applied of the 3 translational dofs (world frame for a free joint),
//                          written before mj_step and zeroed after it (MuJoCo never clears it)
// Errors: mju_user_error throws EngineError (MuJoCo would print and exit); a mj_loadXML failure is
// an EngineError with MuJoCo's message; a warning counted in d->warning during a step (bad qpos,
// qvel, qacc: MuJoCo then resets the state, hiding the instability) is an EngineError "MuJoCo
// warning: ...". The warning handler only records the text: throwing from it would leave mj_step
// half done. Contacts (soft, docs/engines.md 5): box and sphere geoms, solimp "0.9999 0.9999 0.001"
// (impedance ~1: stiff), solref "2h 1" (time constant 2h, the smallest MuJoCo accepts without
// disabling refsafe; critically damped) or, with the scene's restitution, the same stiffness with
// the damping of a spring-damper that returns e (MuJoCo has no coefficient of restitution), the
// scene's friction on every geom (MuJoCo mixes by max), all
// declared once in harness/core/mujoco_world.hpp, where the re-solve of the step reads them.
// Landing, measured (unit cube from 10 m onto a box floor, no drag, 60 Hz): collisions are found at
// the start of a step (no continuous collision), so the step that crosses the floor ends 0.218 m
// inside it (step 84, t_c = 1.392 s) and the contact acts from step 85. The penetration then
// shrinks by a factor 1 - h^2*k/2 = 0.875 per step (k = 1/(2h)^2; the box-box collider reports half
// the depth), with no rebound (highest 0.49999993 m); still (|v| <= 1e-3 m/s) from t = 2.38 s (1.82
// s at 1/120, 3.43 s at 1/30). A dampratio below 1 recovers faster but pops the cube up: 0.14 m at
// 0.8, 2 m at 0.5. Rest offset -7.9e-8 m.
#include <mujoco/mujoco.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <locale>
#include <mutex>
#include <optional>
#include <sstream>
#include <vector>

#include "adapters.hpp"
#include "harness/core/mujoco_world.hpp"
#include "harness/io/xml_text.hpp"

namespace dropcheck {
namespace {

// Resting centre relative to floor top + half extent: the soft contact's steady sag with solimp
// 0.9999, measured -7.9e-8 m at 1/60 (-5.2e-7 at 1/30, -2.1e-8 at 1/120, -5.3e-9 at 1/240: ~h^2)
// for a unit cube dropped from 10 m on a box floor, after 5 s.
constexpr double kRestOffset = 0.0;
// Measured worst |rest| 5.2e-7 m (1/30); the band leaves room for coarser steps (sag ~ h^2).
constexpr double kRestTolerance = 1e-4;

// mju_error must not return (MuJoCo would go on with a broken state): throw through MuJoCo's
// frames.
[[noreturn]] void throw_mujoco_error(const char* msg) {
  throw EngineError(std::string("MuJoCo error: ") + msg);
}

// The text of the last warning MuJoCo printed on this thread; the step turns it into an error.
thread_local std::string t_last_warning;

void record_mujoco_warning(const char* msg) {
  t_last_warning = msg;
}

// MuJoCo's handlers are process-wide function pointers; installed once, never restored.
void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = throw_mujoco_error;
    mju_user_warning = record_mujoco_warning;
  });
}

using ModelPtr = std::unique_ptr<mjModel, decltype(&mj_deleteModel)>;
using DataPtr = std::unique_ptr<mjData, decltype(&mj_deleteData)>;

// Numbers as text that reads back to the same double.
std::string num(double x) {
  std::ostringstream s;
  s.imbue(std::locale::classic());
  s.precision(17);
  s << x;
  return s.str();
}

std::string vec(const Vec3& v) {
  return num(v.x()) + " " + num(v.y()) + " " + num(v.z());
}

// The geoms' defaults: no collision at all without contacts; else the world's soft contact
// (harness/core/mujoco_world.hpp).
std::string geom_defaults(const MujocoWorld& w) {
  if (!w.contacts) return R"(<default><geom contype="0" conaffinity="0"/></default>)";
  const MujocoSoftContact& c = w.contact;
  return R"(<default><geom solimp=")" + num(c.solimp[0]) + " " + num(c.solimp[1]) + " " +
         num(c.solimp[2]) + " " + num(c.solimp[3]) + " " + num(c.solimp[4]) + R"(" solref=")" +
         num(c.solref[0]) + " " + num(c.solref[1]) + R"("/></default>)";
}

// A geom's friction: its sliding value and MuJoCo's default torsional and rolling ones.
std::string friction_xml(const MujocoBody& b) {
  return R"( friction=")" + num(b.friction) + " " + num(kMujocoTorsionalFriction) + " " +
         num(kMujocoRollingFriction) + R"(")";
}

// A body's geom: a sphere of its radius or a box of its half extents.
std::string shape_xml(const MujocoBody& b) {
  return b.radius > 0.0 ? R"( type="sphere" size=")" + num(b.radius) + R"(")"
                        : R"( type="box" size=")" + vec(b.half_extents) + R"(")";
}

// A static body is a box geom of the worldbody; a dynamic one a body with a free joint, its exact
// inertial and its geom. Both are named after the scene's body (MuJoCo's messages name them).
std::string body_xml(const MujocoBody& b) {
  const std::string name = R"( name=")" + xml_escape(b.name) + R"(")";
  if (b.is_static)
    return "<geom" + name + friction_xml(b) + shape_xml(b) + R"( pos=")" + vec(b.position) +
           R"("/>)";
  // The free joint's damping b on all six dofs; load() sets the rotational three's.
  return "<body" + name + R"( pos=")" + vec(b.position) + R"(">)" +
         R"(<joint type="free" damping=")" + num(b.damping) + R"("/>)" +
         R"(<inertial pos="0 0 0" mass=")" + num(b.mass) + R"(" diaginertia=")" + vec(b.inertia) +
         R"("/>)" + "<geom" + friction_xml(b) + shape_xml(b) + "/></body>";
}

// The world as MJCF.
std::string model_xml(const MujocoWorld& w) {
  std::string xml = R"(<mujoco model="dropcheck"><option timestep=")" + num(w.h) +
                    R"(" gravity=")" + vec(w.gravity) + R"(" integrator="Euler" tolerance=")" +
                    num(w.tolerance) + R"(" impratio=")" + num(w.contact.impratio) + R"(" cone=")" +
                    (w.contact.pyramidal ? "pyramidal" : "elliptic") + R"("/>)" + geom_defaults(w) +
                    "<worldbody>";
  for (const MujocoBody& b : w.bodies) xml += body_xml(b);
  return xml + "</worldbody></mujoco>";
}

// MuJoCo's multi-line message on one line ("Error: ...; Object name = cube, ...").
std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (std::size_t p; (p = text.find('\n')) != std::string::npos;) text.replace(p, 1, "; ");
  return text;
}

// mj_loadXML from a virtual file holding `xml`; an EngineError with MuJoCo's message on failure.
ModelPtr load_xml(const std::string& xml) {
  static constexpr const char* kName = "dropcheck_scene.xml";
  // ~2 MB: on the heap; mj_deleteVFS frees the file data even when loading throws.
  std::unique_ptr<mjVFS, void (*)(mjVFS*)> vfs(new mjVFS(), [](mjVFS* v) {
    mj_deleteVFS(v);
    delete v;
  });
  mj_defaultVFS(vfs.get());
  if (mj_makeEmptyFileVFS(vfs.get(), kName, static_cast<int>(xml.size())) != 0)
    throw EngineError("MuJoCo: cannot create the virtual model file");
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), kName)], xml.data(), xml.size());
  char error[1000] = "";
  ModelPtr m(mj_loadXML(kName, vfs.get(), error, sizeof error), mj_deleteModel);
  if (!m) throw EngineError("MuJoCo cannot load the model: " + one_line(error));
  // A compiler warning on a generated model means the generator is wrong.
  if (error[0] != '\0') throw EngineError("MuJoCo model warning: " + one_line(error));
  return m;
}

class MujocoEngine final : public Engine {
 public:
  MujocoEngine() { install_handlers(); }
  // For tests: every load() builds its contacts with `contact` and its solver's `tolerance` instead
  // of the adapter's.
  MujocoEngine(const MujocoSoftContact& contact, double tolerance)
      : contact_(contact), tolerance_(tolerance) {
    install_handlers();
  }

  EngineInfo info() const override;
  void load(const Scene& scene, double h) override;
  void set_forces(std::span<const Vec3> forces) override;
  void set_torques(std::span<const Vec3> torques) override;
  void step() override;
  void read(std::span<BodyState> out) const override;
  void read_rotation(std::span<RotationState> out) const override;
  bool use_body_materials() override { return body_materials_ = true; }

  // Seconds of `steps` calls of mj_step alone (bare_step_loop in adapters.hpp).
  double bare_seconds(std::int64_t steps) {
    const auto start = std::chrono::steady_clock::now();
    for (std::int64_t n = 0; n < steps; ++n) mj_step(m_.get(), d_.get());
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  // MuJoCo's body_mass of scene body i (dynamic bodies only), for tests.
  double mass_of(std::size_t i) const { return m_->body_mass[m_->jnt_bodyid[joint_.at(i)]]; }

 private:
  static std::vector<int> free_joints(mjModel& m, const MujocoWorld& w);
  void check_warnings();

  ModelPtr m_{nullptr, mj_deleteModel};
  DataPtr d_{nullptr, mj_deleteData};
  std::vector<int> joint_;        // free joint of each scene body; -1 for static bodies
  std::vector<Vec3> static_pos_;  // static bodies do not move
  std::array<int, mjNWARNING> warnings_{};
  bool body_materials_ = false;               // Engine::use_body_materials
  std::optional<MujocoSoftContact> contact_;  // a test's soft contact, instead of the adapter's
  std::optional<double> tolerance_;           // a test's solver tolerance
};

EngineInfo MujocoEngine::info() const {
  EngineInfo i;
  i.name = "mujoco";
  i.version = mj_versionString();
  i.scalar = Scalar::f64;
  i.capabilities = {.contacts = true,
                    .planar_only = false,
                    .rotation = Rotation::full,
                    .friction = true,
                    .restitution = true,
                    .spheres = true};
  i.law = DampingOrder::AfterForces;
  i.rotation_law = {Gyroscopic::explicit_term, OrientationUpdate::exponential_map};
  i.damping_mapping =
      "free joint damping b = m*(exp(k*h) - 1)/h, rotational dofs I_i*(exp(k_a*h) - 1)/h; Euler";
  i.contact_settings =
      "box and sphere geoms, solimp 0.9999 0.9999 0.001, solref 2h 1 (soft, critically damped); "
      "restitution e as the direct solref -1/(2h)^2 -zeta/h, zeta = -ln e/sqrt(pi^2 + ln^2 e) "
      "(a spring-damper returning e); friction mu on every geom (max mix; 0.5 unset), pyramidal "
      "cone, impratio 1";
  // The pyramid's edges are n +- mu*t_i on the contact frame's two tangents
  // (engine_core_constraint.c mj_instantiateContact): |f_1| + |f_2| <= mu*N.
  i.friction_model = FrictionModel::sum_pyramid;
  i.contact_solver = {.kind = ContactSolverKind::mujoco_2_2};
  i.rest_offset = kRestOffset;
  i.rest_tolerance = kRestTolerance;
  // A stack: the soft contact's steady sag (1 - d)*tau^2*A*f per pyramid edge, with d = 0.9999,
  // tau = 2h, A = (1 + mu^2)*(1/m_a + 1/m_b) and 4 edges at each of 4 points sharing the weight.
  // Read in engine_core_constraint.c (2.2.1): mj_diagApprox gives a pyramid edge tran + fri^2*tran
  // (tran the bodies' body_invweight0), mj_makeImpedance R = (1 - imp)/imp*diagApprox and
  // K = 1/(dmax^2*timeconst^2*dampratio^2); at rest R*f = K*imp*depth. Measured on mass_ratio at
  // 1/240: 5.317e-4 m under 1e5 kg, 1.000 of it; at 1/60 its heaviest stacks settle slowly
  // (0.84-1.000 of it after 5 s).
  // mu is the adapter's 0.5: stacks are judged only with the adapter's own friction (identify
  // --combine, which writes each body's, judges no stack).
  i.stack_law = {.soft = 1e-4 * (1.0 + 0.5 * 0.5) / 16.0, .tau_steps = 2.0, .sink_bound = 1e-12};
  // mj_collision tests geoms at the current positions only (no sweep): no continuous collision.
  i.continuous_collision = false;
  return i;
}

void MujocoEngine::load(const Scene& scene, double h) {
  d_.reset();  // a failed load leaves no engine behind, not a half-built one
  m_.reset();
  t_last_warning.clear();
  MujocoWorld world = mujoco_world(scene, h, body_materials_);
  if (contact_) world.contact = *contact_;
  if (tolerance_) world.tolerance = *tolerance_;
  ModelPtr m = load_xml(model_xml(world));
  joint_ = free_joints(*m, world);
  DataPtr d(mj_makeData(m.get()), mj_deleteData);
  if (!d) throw EngineError("MuJoCo: mj_makeData failed");
  static_pos_.clear();
  for (std::size_t i = 0; i < joint_.size(); ++i) {
    const Body& b = scene.bodies[i];
    static_pos_.push_back(b.position);
    if (joint_[i] < 0) continue;
    // Free joint: qpos = (x, y, z, qw, qx, qy, qz), qvel = (vx, vy, vz, wx, wy, wz).
    std::memcpy(d->qpos + m->jnt_qposadr[joint_[i]], b.position.data(), 3 * sizeof(mjtNum));
    std::memcpy(d->qvel + m->jnt_dofadr[joint_[i]], b.velocity.data(), 3 * sizeof(mjtNum));
    mjtNum* q = d->qpos + m->jnt_qposadr[joint_[i]] + 3;
    const Quat& o = b.orientation;
    q[0] = o.w(), q[1] = o.x(), q[2] = o.y(), q[3] = o.z();
    const Vec3 w_body = o.conjugate() * b.angular_velocity;
    std::memcpy(d->qvel + m->jnt_dofadr[joint_[i]] + 3, w_body.data(), 3 * sizeof(mjtNum));
  }
  m_ = std::move(m);
  d_ = std::move(d);
  warnings_.fill(0);
}

// The free joint of each dynamic body (-1 for static ones), found through the body's name; its
// rotational dofs damped as the world says (I_i*(exp(k_a*h) - 1)/h).
std::vector<int> MujocoEngine::free_joints(mjModel& m, const MujocoWorld& w) {
  std::vector<int> joints(w.bodies.size(), -1);
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    if (w.bodies[i].is_static) continue;
    const int body = mj_name2id(&m, mjOBJ_BODY, w.bodies[i].name.c_str());
    if (body < 0 || m.body_jntnum[body] != 1)
      throw EngineError("MuJoCo: no free joint for body '" + w.bodies[i].name + "'");
    joints[i] = m.body_jntadr[body];
    const int dof = m.jnt_dofadr[joints[i]];
    for (int r = 3; r < 6; ++r) m.dof_damping[dof + r] = w.bodies[i].angular_damping[r - 3];
  }
  return joints;
}

void MujocoEngine::set_forces(std::span<const Vec3> forces) {
  if (!d_) return;  // step() reports it
  for (std::size_t i = 0; i < joint_.size(); ++i)
    if (joint_[i] >= 0)
      std::memcpy(d_->qfrc_applied + m_->jnt_dofadr[joint_[i]], forces[i].data(),
                  3 * sizeof(mjtNum));
}

// World-frame torques as xfrc_applied's torque part (MuJoCo turns them into body axes).
void MujocoEngine::set_torques(std::span<const Vec3> torques) {
  if (!d_) return;  // step() reports it
  for (std::size_t i = 0; i < joint_.size(); ++i)
    if (joint_[i] >= 0)
      std::memcpy(d_->xfrc_applied + 6 * m_->jnt_bodyid[joint_[i]] + 3, torques[i].data(),
                  3 * sizeof(mjtNum));
}

void MujocoEngine::step() {
  if (!d_) throw EngineError("MuJoCo: no model loaded (or the last one failed)");
  t_last_warning.clear();
  try {
    mj_step(m_.get(), d_.get());
  } catch (...) {
    d_.reset();  // mju_error unwound out of mj_step: its state is not to be trusted any more
    throw;
  }
  // The applied forces persist in mjData: this step's force must not act on the next one.
  mju_zero(d_->qfrc_applied, m_->nv);
  mju_zero(d_->xfrc_applied, 6 * m_->nbody);
  check_warnings();
}

// A warning counted during the call (mj_warning increments d->warning[i].number and prints only the
// first time) is an error: on bad qpos/qvel/qacc MuJoCo resets the state, which would hide it.
void MujocoEngine::check_warnings() {
  for (int i = 0; i < mjNWARNING; ++i) {
    const int n = d_->warning[i].number;
    if (n == warnings_[i]) continue;
    warnings_[i] = n;
    const std::string text = t_last_warning.empty()
                                 ? std::string(mju_warningText(i, d_->warning[i].lastinfo))
                                 : t_last_warning;
    throw EngineError("MuJoCo warning: " + text);
  }
  if (!t_last_warning.empty()) throw EngineError("MuJoCo warning: " + t_last_warning);
}

void MujocoEngine::read(std::span<BodyState> out) const {
  if (!d_) throw EngineError("MuJoCo: no model loaded (or the last one failed)");
  for (std::size_t i = 0; i < joint_.size(); ++i) {
    if (joint_[i] < 0) {
      out[i] = {static_pos_[i], Vec3::Zero()};
      continue;
    }
    const mjtNum* q = d_->qpos + m_->jnt_qposadr[joint_[i]];
    const mjtNum* v = d_->qvel + m_->jnt_dofadr[joint_[i]];
    out[i].position = Vec3(q[0], q[1], q[2]);
    out[i].velocity = Vec3(v[0], v[1], v[2]);
  }
}

// Orientation qpos[3..6]; world angular velocity R*w_b from the body-frame qvel[3..5].
void MujocoEngine::read_rotation(std::span<RotationState> out) const {
  if (!d_) throw EngineError("MuJoCo: no model loaded (or the last one failed)");
  for (std::size_t i = 0; i < joint_.size(); ++i) {
    out[i] = RotationState{};
    if (joint_[i] < 0) continue;
    const mjtNum* q = d_->qpos + m_->jnt_qposadr[joint_[i]] + 3;
    const mjtNum* w = d_->qvel + m_->jnt_dofadr[joint_[i]] + 3;
    out[i].orientation = Quat(q[0], q[1], q[2], q[3]);
    out[i].angular_velocity = out[i].orientation * Vec3(w[0], w[1], w[2]);
  }
}

}  // namespace

std::unique_ptr<Engine> make_mujoco() {
  return std::make_unique<MujocoEngine>();
}

double bare_seconds_mujoco(const Scene& scene, double h) {
  MujocoEngine e;
  e.load(scene, h);
  return e.bare_seconds(step_count(scene, h));
}

// For tests (tests/adapters/mujoco_test.cpp): body_mass of scene body i of a loaded mujoco engine.
double mujoco_body_mass(const Engine& engine, std::size_t body) {
  return dynamic_cast<const MujocoEngine&>(engine).mass_of(body);
}

// For tests: a mujoco engine whose contacts are `contact` (another cone, impratio, solref) and
// whose solver stops at `tolerance`.
std::unique_ptr<Engine> make_mujoco_with_contact(const MujocoSoftContact& contact,
                                                 double tolerance) {
  return std::make_unique<MujocoEngine>(contact, tolerance);
}

// For tests: raises mju_error(msg) through the adapter's handler (it must throw, not exit).
void mujoco_raise_error(const char* msg) {
  install_handlers();
  mju_error(msg);
}

}  // namespace dropcheck
