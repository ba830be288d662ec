// Scene: the validated, engine-neutral description of one drop-cube experiment, in SI units.
// It is the lingua franca between the TOML loader, the adapters and the references.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace dropcheck {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

// A step size as the user wrote it ("1/60" or "0.01") and its value in seconds.
struct Timestep {
  double seconds = 1.0 / 60.0;
  std::string text = "1/60";
};

// A body's collision shape. A sphere's half_extents are (r, r, r): its bounding box.
enum class Shape { box, sphere };

struct Body {
  std::string name;
  Shape shape = Shape::box;
  double radius = 0.0;               // m, a sphere's (> 0); 0 for a box
  Vec3 half_extents{0.5, 0.5, 0.5};  // m
  double mass = 1.0;                 // kg, > 0
  Vec3 position = Vec3::Zero();      // m, centre of the box
  Vec3 velocity = Vec3::Zero();      // m/s
  bool is_static = false;
  // Rotation. A scene that gives none of these keys does not rotate (needs_rotation is false) and
  // runs exactly as a translation-only scene.
  Quat orientation = Quat::Identity();   // unit quaternion, body frame to world frame
  Vec3 angular_velocity = Vec3::Zero();  // rad/s, world frame
  Vec3 inertia = Vec3::Zero();  // principal moments in the body frame, kg m^2 (the loader sets
                                // them: given, or a uniform box); zero: a uniform box (inertia_of)
  // Contact material (docs/contact.md): one value per scene (scene_material). Unset: each engine
  // keeps the contact settings its adapter documents (EngineInfo::contact_settings); set: an engine
  // runs the scene only if its adapter maps it (Capabilities::friction, ::restitution), so that
  // every contact's effective value under the engine's combine rule is the scene's.
  std::optional<double> friction = std::nullopt;     // Coulomb coefficient mu, >= 0
  std::optional<double> restitution = std::nullopt;  // coefficient e in [0, 1]
};

// The principal moments of a uniform box of mass m and half extents h: m/3*(hy^2 + hz^2) about x
// and cyclic (m/12*(b^2 + c^2) with full sides b = 2*hy, c = 2*hz).
Vec3 box_inertia(double mass, const Vec3& half_extents);

// The principal moments of a uniform sphere: 2/5*m*r^2 about every axis.
Vec3 sphere_inertia(double mass, double radius);

// The body's principal moments: `inertia` when set (every moment > 0), else its uniform shape's (a
// body built in code without them). What every adapter and oracle uses.
Vec3 inertia_of(const Body& b);

// Heights (y) of the top and bottom of the body's bounding box, as placed in the scene.
inline double top_of(const Body& b) {
  return b.position.y() + b.half_extents.y();
}
inline double bottom_of(const Body& b) {
  return b.position.y() - b.half_extents.y();
}

// F = constant (N), every step.
struct ConstantForce {
  Vec3 force = Vec3::Zero();
};

// Spring to a fixed anchor, with a dashpot on the body's velocity:
//   d = x - anchor;  F = -stiffness*(|d| - rest_length)*d/|d| - damping*v
// With rest_length = 0 this is F = -stiffness*d - damping*v (a linear, isotropic oscillator).
struct Spring {
  Vec3 anchor = Vec3::Zero();  // m
  double stiffness = 0.0;      // N/m, >= 0
  double damping = 0.0;        // N*s/m, >= 0
  double rest_length = 0.0;    // m, >= 0
};

struct Force {
  std::vector<std::size_t> bodies;  // indices into Scene::bodies (dynamic bodies only)
  std::variant<ConstantForce, Spring> law;
};

// tau = constant (N m, world frame), every step, on each body listed.
struct Torque {
  std::vector<std::size_t> bodies;  // indices into Scene::bodies (dynamic bodies only)
  Vec3 torque = Vec3::Zero();
};

// A figure someone published for this scene, with the rotational member that predicts it: the
// report runs that member and puts the published figure, the prediction and today's engines side
// by side ([[published]] in a scene file).
struct PublishedFigure {
  std::string source;               // where it was published ("Gazebo physics benchmark, ...")
  std::string engine;               // whose figure it is ("ODE (Gazebo, 2015)")
  double dt = 0.0;                  // the step it was published at (s)
  double max_momentum_drift = 0.0;  // max |L(t) - L(0)| / |L(0)|, as published
  std::string law;                  // rotation_law_key of the member that predicts it
  double law_dt = 0.0;  // the step that member runs at (dt; Simbody's two half steps: dt/2)
  std::string note;     // why that member, in a sentence
};

// A figure a scene's [expect] table states (docs/design.md, "Scenario files"): its value and its
// text as the file writes it ("2.5510", "1e-5"), which the description quotes where it writes the
// figure's {name}.
struct ExpectedFigure {
  double value = 0.0;
  std::string text;
};

struct World {
  Vec3 gravity = Vec3::Zero();        // m/s^2, y up
  double damping_rate = 0.0;          // k in 1/s: dv/dt = ... - k*v; per-step decay phi = exp(-k*h)
  double angular_damping_rate = 0.0;  // the same for the angular velocity: dw/dt = ... - k_a*w
  bool contacts = false;              // false: no collision shapes at all
};

struct Scene {
  std::string name;
  std::string description;  // as the report prints it: every {name} replaced by expect's text
  std::string source;       // file the scene came from ("" when built in code)
  double duration = 0.0;    // simulated seconds
  Timestep timestep;        // default step
  std::vector<Timestep> timesteps;  // sweep; never empty after loading (holds at least `timestep`)
  World world;
  std::vector<Body> bodies;
  std::vector<Force> forces;
  std::vector<Torque> torques;
  std::vector<PublishedFigure> published;
  // [expect]: name -> figure, a body's figures named "<body>.<quantity>" ([expect.<body>]).
  std::map<std::string, ExpectedFigure> expect;
  double tolerance = 1e-3;  // m: |dx| above this counts as diverged (time to divergence)
};

// Whole steps of size h in the scene's duration: round(duration / h).
std::int64_t step_count(const Scene& scene, double h);

// Per-step velocity factor phi = exp(-k*h) for the scene's damping rate k.
double decay_per_step(const Scene& scene, double h);

// The same for the angular velocity: exp(-k_a*h) for the scene's angular damping rate k_a.
double angular_decay_per_step(const Scene& scene, double h);

// True when every body, velocity, force and gravity lies in the x-y plane (z components zero).
bool is_planar(const Scene& scene);

// True when some body starts turned or turning, or a torque acts: then the scene's outcome depends
// on rotation, and an engine that does not rotate bodies cannot run it.
bool needs_rotation(const Scene& scene);

// True when a force of the scene (constant or spring) acts on body `body`.
bool pushed(const Scene& scene, std::size_t body);

// A scene's contact material: one friction and one restitution for every contact (the loader
// refuses two bodies that set different values; docs/contact.md). Unset: the engines' defaults.
struct Material {
  std::optional<double> friction;
  std::optional<double> restitution;
};
Material scene_material(const Scene& scene);

// True when some body is a sphere.
bool has_spheres(const Scene& scene);

// True when every rotation of the scene is about z: orientations about z, angular velocities and
// torques along z (what a 2-D engine can turn).
bool spins_about_z(const Scene& scene);

}  // namespace dropcheck
