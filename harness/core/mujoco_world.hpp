// What the mujoco adapter (adapters/mujoco.cpp) builds from a scene, as MuJoCo's own parameters:
// declared once, for the adapter that writes the model and for the re-solve of MuJoCo's step that
// predicts it (harness/oracles/mujoco_step.hpp).
//
//   step, gravity       <option timestep="h" gravity="g" integrator="Euler"/>, y up as the scene's
//   damping             b = m*(exp(k*h) - 1)/h on the free joint's 3 translational dofs and
//                       I_i*(exp(k_a*h) - 1)/h on its 3 rotational ones: mj_Euler's implicit
//                       v/(1 + h*b/m) is then exp(-k*h)
//   dynamic body        a body with a free joint, inertial mass m and diaginertia (Ixx, Iyy, Izz),
//                       one box geom of the half extents or one sphere geom of the radius
//   static body         a box geom of the worldbody
//   friction            the scene's mu as every geom's sliding friction (0.5 unset), torsional
//                       0.005 and rolling 0.0001 (MuJoCo's defaults): MuJoCo takes the larger of
//                       two geoms' values, so every pair gets mu
//   soft contact        solref (2h, 1): time constant 2h (the smallest refsafe lets through) and
//                       critically damped; with the scene's restitution e, the same stiffness and
//                       the damping of a spring-damper that returns e (restitution_solref below);
//                       solimp (0.9999, 0.9999, 0.001, 0.5, 2): impedance
//                       0.9999 at every depth (stiff); impratio 1; pyramidal cone; condim 3
//   solver              Newton, tolerance 1e-8 (MuJoCo's defaults): its iterate stops up to 5e-12
//                       of the velocity away from the step problem's minimum (measured on
//                       slide_stop and slide_diagonal at 1/60 and 1/240; 1e-15 would bring it to
//                       rounding, and settles mass_ratio's 1000 kg stack at 1/60 more slowly: 0.74
//                       of its sag after 5 s instead of 0.84)
#pragma once

#include <array>
#include <string>
#include <vector>

#include "harness/core/scene.hpp"

namespace dropcheck {

// MuJoCo's soft contact (engine_core_constraint.c, getsolparam and mj_makeImpedance): each
// contact's rows get the impedance imp = solimp, R = (1 - imp)/imp * diagApprox, and the reference
// acceleration aref = -B*(J*v) - K*imp*dist. solref in the standard format (timeconst, dampratio),
// both positive: K = 1/(dmax^2*timeconst^2*dampratio^2), B = 2/(dmax*timeconst), the time constant
// raised to 2h at least (refsafe). In the direct format (-stiffness, -damping), neither positive:
// K = stiffness/dmax^2, B = damping/dmax.
struct MujocoSoftContact {
  std::array<double, 2> solref{0.02, 1.0};  // MuJoCo's default
  std::array<double, 5> solimp{0.9999, 0.9999, 0.001, 0.5, 2.0};
  double impratio = 1.0;
  bool pyramidal = true;  // <option cone="pyramidal"> (MuJoCo's default), else elliptic
};

struct MujocoBody {
  std::string name;
  bool is_static = false;
  double radius = 0.0;  // > 0: a sphere geom, else a box
  Vec3 half_extents = Vec3::Zero();
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();        // qpos (w, x, y, z)
  Vec3 velocity = Vec3::Zero();               // qvel[0..2], world frame
  Vec3 angular_velocity_body = Vec3::Zero();  // qvel[3..5], body frame
  double mass = 0.0;                          // dynamic bodies only
  Vec3 inertia = Vec3::Zero();                // diaginertia
  double friction = 0.0;                      // the geom's sliding friction
  double damping = 0.0;                       // b of each translational dof (N s/m)
  Vec3 angular_damping = Vec3::Zero();        // b of each rotational dof (N m s)
};

struct MujocoWorld {
  double h = 0.0;
  double tolerance = 1e-8;  // <option tolerance>: the Newton solver's stopping rule
  Vec3 gravity = Vec3::Zero();
  bool contacts = false;  // false: contype = conaffinity = 0 on every geom
  MujocoSoftContact contact;
  std::vector<MujocoBody> bodies;  // in the scene's order
};

// The sliding friction of every geom when the scene sets none.
inline constexpr double kMujocoDefaultFriction = 0.5;
// MuJoCo's default torsional and rolling friction, written beside the sliding one.
inline constexpr double kMujocoTorsionalFriction = 0.005;
inline constexpr double kMujocoRollingFriction = 0.0001;

// Restitution e as a direct solref (-K, -B) at step h. A contact row pushes the body as the linear
// spring-damper r'' = -B*r' - K*r (with impedance ~1 the solver meets aref), which leaves after one
// half oscillation with e = exp(-zeta*pi/sqrt(1 - zeta^2)) of the speed it met, zeta = B/(2*w0)
// and w0^2 = K: so zeta = -ln(e)/sqrt(pi^2 + ln(e)^2), 1 (critical, no rebound) at e = 0 and 0 at
// e = 1. K = 1/(2h)^2 is the adapter's contact without restitution (solref (2h, 1)) and B = 2*zeta*
// sqrt(K) = zeta/h: e = 0 is that contact again. The step resolves the oscillation (w0*h = 1/2,
// about 6 steps per half period) but only to first order: a bounce's own figure is MuJoCo's step
// re-solved, and its distance from e is the physics' error, reported beside it.
MujocoSoftContact restitution_solref(double e, double h);

// `scene` at step h as the adapter builds it. With `body_materials` (identify --combine) each geom
// carries its body's own friction where it sets one, so that MuJoCo's max makes each pair's value.
MujocoWorld mujoco_world(const Scene& scene, double h, bool body_materials = false);

}  // namespace dropcheck
