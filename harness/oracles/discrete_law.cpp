#include "harness/oracles/discrete_law.hpp"

#include <cmath>
#include <vector>

#include "harness/core/forces.hpp"
#include "harness/oracles/analytic.hpp"

namespace dropcheck {
namespace {

using Real = long double;
using VecL = Eigen::Matrix<Real, 3, 1>;

struct StateL {
  VecL x, v;
};

// The error-controlled member's law is the continuous model (law.hpp): its closed form, or, for a
// scene without one, a trajectory that says so (status engine_error, no samples past step 0).
Trajectory continuous_law(Law law, const Scene& scene, double h, const RunOptions& options) {
  std::optional<Trajectory> exact = analytic_trajectory(scene, h, options);
  if (!exact) {
    Trajectory t;
    t.scene = scene.name;
    t.h = h;
    t.steps = step_count(scene, h);
    t.status = RunStatus::engine_error;
    t.failure = "no closed form to follow: " + analytic_unavailable(scene);
    exact = std::move(t);
  }
  exact->engine = "law: " + to_string(law);
  return *exact;
}

}  // namespace

Trajectory predict_discrete(Law law, const Scene& scene, double h, const RunOptions& options) {
  if (law.scheme == Scheme::ErrorControlled) return continuous_law(law, scene, h, options);
  Trajectory t;
  t.engine = "law: " + to_string(law);
  t.scene = scene.name;
  t.h = h;
  t.steps = step_count(scene, h);
  for (const Body& b : scene.bodies) t.body_names.push_back(b.name);
  const std::size_t nb = scene.bodies.size();
  const std::int64_t every = options.record_every < 1 ? 1 : options.record_every;

  // phi = exp(-k*h) in long double; the engines round the same value to their own scalar.
  const Real rate = static_cast<Real>(scene.world.damping_rate), hl = static_cast<Real>(h);
  const Real phi = std::exp(-rate * hl);
  const auto springs = springs_by_body(scene);
  const VecL g = scene.world.gravity.cast<Real>();
  std::vector<StateL> s(nb);
  std::vector<BodyState> start(nb);
  std::vector<Vec3> forces(nb);
  for (std::size_t i = 0; i < nb; ++i)
    s[i] = {scene.bodies[i].position.cast<Real>(), scene.bodies[i].velocity.cast<Real>()};

  auto snapshot = [&](std::int64_t n) {
    t.recorded.push_back(n);
    for (const StateL& b : s) t.states.push_back({b.x.cast<double>(), b.v.cast<double>()});
  };
  snapshot(0);
  for (std::int64_t n = 1; n <= t.steps; ++n) {
    for (std::size_t i = 0; i < nb; ++i) start[i] = {s[i].x.cast<double>(), s[i].v.cast<double>()};
    compute_forces(scene, start, forces);
    for (std::size_t i = 0; i < nb; ++i) {
      if (scene.bodies[i].is_static) continue;
      const Real m = static_cast<Real>(scene.bodies[i].mass);
      if (law.scheme == Scheme::RK4) {
        // Forces at each stage: the step-start force with the springs' change (forces.hpp).
        const auto a = [&](const VecL& x, const VecL& v) -> VecL {
          const BodyState now{x.cast<double>(), v.cast<double>()};
          return g + stage_force(forces[i], springs[i], start[i], now).cast<Real>() / m;
        };
        advance_rk4(rate, hl, a, s[i].x, s[i].v);
        continue;
      }
      const VecL a = g + forces[i].cast<Real>() / m;
      advance(law, phi, hl, a, s[i].x, s[i].v);
    }
    if (n % every == 0 || n == t.steps) snapshot(n);
  }
  return t;
}

}  // namespace dropcheck
