#include "harness/run/run_limits.hpp"

#include <cfloat>
#include <cmath>
#include <vector>

#include "harness/core/number_format.hpp"
#include "harness/core/timestep.hpp"

namespace dropcheck {
namespace {

// A scene value an engine receives, named as a user reads it.
struct NamedValue {
  std::string name;
  double value;
};

void add(std::vector<NamedValue>& out, const std::string& name, const Vec3& v) {
  for (int i = 0; i < 3; ++i) out.push_back({name + "[" + std::to_string(i) + "]", v[i]});
}

// Every number of the scene that reaches an engine.
std::vector<NamedValue> engine_values(const Scene& scene) {
  std::vector<NamedValue> out;
  add(out, "world.gravity", scene.world.gravity);
  out.push_back({"world damping rate k", scene.world.damping_rate});
  out.push_back({"world angular damping rate k_a", scene.world.angular_damping_rate});
  for (const Body& b : scene.bodies) {
    const std::string at = "body '" + b.name + "' ";
    out.push_back({at + "mass", b.mass});
    add(out, at + "half_extents", b.half_extents);
    add(out, at + "position", b.position);
    add(out, at + "velocity", b.velocity);
    add(out, at + "angular_velocity", b.angular_velocity);
    add(out, at + "inertia", inertia_of(b));
  }
  for (std::size_t i = 0; i < scene.torques.size(); ++i)
    add(out, "torque[" + std::to_string(i) + "] torque", scene.torques[i].torque);
  for (std::size_t i = 0; i < scene.forces.size(); ++i) {
    const std::string at = "force[" + std::to_string(i) + "] ";
    if (const auto* c = std::get_if<ConstantForce>(&scene.forces[i].law)) {
      add(out, at + "force", c->force);
    } else if (const auto* s = std::get_if<Spring>(&scene.forces[i].law)) {
      add(out, at + "anchor", s->anchor);
      out.push_back({at + "stiffness", s->stiffness});
      out.push_back({at + "damping", s->damping});
      out.push_back({at + "rest_length", s->rest_length});
    }
  }
  return out;
}

std::string step_refusal(const Scene& scene, double h) {
  const double n = scene.duration / h;
  if (n <= static_cast<double>(kMaxSteps)) return "";
  return g3(n) + " steps at h = " + g3(h) + " s exceed the limit of " + std::to_string(kMaxSteps) +
         " steps per run";
}

std::string memory_refusal(const Scene& scene, double h, const RunOptions& options) {
  const double samples =
      static_cast<double>(recorded_samples(step_count(scene, h), options.record_every));
  const double bytes = trajectory_bytes(samples, scene.bodies.size(), needs_rotation(scene));
  if (bytes <= static_cast<double>(kTrajectoryBudgetBytes)) return "";
  return "the recorded trajectory would take " + g3(bytes / (1 << 30)) + " GiB (" + g3(samples) +
         " samples x " + std::to_string(scene.bodies.size()) + " bodies), over the budget of " +
         g3(double(kTrajectoryBudgetBytes) / (1 << 30)) +
         " GiB per run; shorten the duration, use a larger step or record fewer steps";
}

std::string float_refusal(const EngineInfo& engine, const Scene& scene) {
  if (engine.scalar != Scalar::f32) return "";
  for (const NamedValue& v : engine_values(scene))
    if (std::abs(v.value) > static_cast<double>(FLT_MAX))
      return v.name + " = " + g3(v.value) + " exceeds the float range of " + engine.name +
             " (f32, largest " + g3(FLT_MAX) + ")";
  // A moment of inertia that rounds to zero in float would be divided by.
  for (const Body& b : scene.bodies)
    if (needs_rotation(scene) && !b.is_static && inertia_of(b).minCoeff() < FLT_MIN)
      return "body '" + b.name + "' inertia " + g3(inertia_of(b).minCoeff()) +
             " kg m^2 is below the smallest normal float (" + g3(FLT_MIN) + ") of " + engine.name +
             " (f32)";
  return "";
}

}  // namespace

std::int64_t recorded_samples(std::int64_t steps, std::int64_t record_every) {
  const std::int64_t every = record_every < 1 ? 1 : record_every;
  return steps / every + 2;  // step 0, every Nth step, and the last step when it is not an Nth
}

double trajectory_bytes(double samples, std::size_t bodies, bool rotates) {
  const double per_body = sizeof(BodyState) + (rotates ? sizeof(RotationState) : 0.0);
  return samples * (static_cast<double>(bodies) * per_body + sizeof(std::int64_t));
}

std::string run_refusal(const EngineInfo& engine, const Scene& scene, double h,
                        const RunOptions& options) {
  if (std::string why = step_refusal(scene, h); !why.empty()) return why;
  if (std::string why = memory_refusal(scene, h, options); !why.empty()) return why;
  return float_refusal(engine, scene);
}

std::optional<Trajectory> refuse_run(const EngineInfo& engine, const Scene& scene, double h,
                                     const RunOptions& options) {
  const std::string why = run_refusal(engine, scene, h, options);
  if (why.empty()) return std::nullopt;
  return failed_trajectory(engine.name, scene, h, RunStatus::refused, why);
}

}  // namespace dropcheck
