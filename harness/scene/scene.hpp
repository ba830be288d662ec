// Scene: the validated, engine-neutral description of one drop-cube experiment, in SI units.
// It is the lingua franca between the TOML loader, the adapters and the references.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace dropcheck {

using Vec3 = Eigen::Vector3d;

// A step size as the user wrote it ("1/60" or "0.01") and its value in seconds.
struct Timestep {
  double seconds = 1.0 / 60.0;
  std::string text = "1/60";
};

struct Body {
  std::string name;
  Vec3 half_extents{0.5, 0.5, 0.5};  // m
  double mass = 1.0;                 // kg, > 0
  Vec3 position = Vec3::Zero();      // m, centre of the box
  Vec3 velocity = Vec3::Zero();      // m/s
  bool is_static = false;
};

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

struct World {
  Vec3 gravity = Vec3::Zero();  // m/s^2, y up
  double damping_rate = 0.0;    // k in 1/s: dv/dt = ... - k*v; per-step decay phi = exp(-k*h)
  bool contacts = false;        // false: no collision shapes at all
};

struct Scene {
  std::string name;
  std::string description;
  std::string source;               // file the scene came from ("" when built in code)
  double duration = 0.0;            // simulated seconds
  Timestep timestep;                // default step
  std::vector<Timestep> timesteps;  // sweep; never empty after loading (holds at least `timestep`)
  World world;
  std::vector<Body> bodies;
  std::vector<Force> forces;
  double tolerance = 1e-3;  // m: |dx| above this counts as diverged (time to divergence)
};

// Whole steps of size h in the scene's duration: round(duration / h).
std::int64_t step_count(const Scene& scene, double h);

// Per-step velocity factor phi = exp(-k*h) for the scene's damping rate k.
double decay_per_step(const Scene& scene, double h);

// True when every body, velocity, force and gravity lies in the x-y plane (z components zero).
bool is_planar(const Scene& scene);

}  // namespace dropcheck
