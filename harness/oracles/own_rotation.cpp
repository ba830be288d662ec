#include "harness/oracles/own_rotation.hpp"

#include <algorithm>

#include "harness/core/forces.hpp"
#include "harness/core/rotation_metrics.hpp"

namespace dropcheck {
namespace {

using LD = long double;
using VL = Eigen::Matrix<LD, 3, 1>;

RotationState to_state(const Spin<LD>& s) {
  return {s.q.cast<double>(), s.w.cast<double>()};
}

// predict_rotation's loop, from the start orientations `q0` and angular velocities `w0`.
std::vector<RotationState> iterate_rotation(RotationLaw law, Law linear, const Scene& scene,
                                            double h, const std::vector<std::int64_t>& recorded,
                                            const std::vector<Quat>& q0,
                                            const std::vector<VL>& w0) {
  const std::size_t bodies = scene.bodies.size();
  std::vector<Vec3> torques(bodies);
  compute_torques(scene, torques);
  std::vector<Spin<LD>> spins(bodies);
  for (std::size_t b = 0; b < bodies; ++b) {
    spins[b].q = q0[b].cast<LD>();
    spins[b].w = w0[b];
    const Eigen::Matrix<LD, 3, 3> R = spins[b].q.toRotationMatrix();
    const VL I = inertia_of(scene.bodies[b]).cast<LD>();
    spins[b].L = R * I.cwiseProduct(R.transpose() * w0[b]);  // the RK4 member's state
  }
  const LD rate = static_cast<LD>(scene.world.angular_damping_rate);
  const LD phi = std::exp(-rate * LD(h));
  const bool rk4 = linear.scheme == Scheme::RK4;
  std::vector<RotationState> out;
  out.reserve(recorded.size() * bodies);
  std::int64_t step = 0;
  for (const std::int64_t until : recorded) {
    for (; step < until; ++step)
      for (std::size_t b = 0; b < bodies; ++b)
        if (scene.bodies[b].is_static)
          continue;
        else if (rk4)  // RK4 has one rotational member (rotation_law.hpp)
          advance_rotation_rk4<LD>(rate, LD(h), inertia_of(scene.bodies[b]).cast<LD>(),
                                   torques[b].cast<LD>(), spins[b]);
        else
          advance_rotation<LD>(law, linear, phi, LD(h), inertia_of(scene.bodies[b]).cast<LD>(),
                               torques[b].cast<LD>(), spins[b]);
    for (const Spin<LD>& s : spins) out.push_back(to_state(s));
  }
  return out;
}

std::vector<VL> start_spins(const Scene& scene) {
  std::vector<VL> w0;
  for (const Body& b : scene.bodies) w0.push_back(b.angular_velocity.cast<LD>());
  return w0;
}

std::vector<Quat> start_orientations(const Scene& scene) {
  std::vector<Quat> q0;
  for (const Body& b : scene.bodies) q0.push_back(b.orientation);
  return q0;
}

}  // namespace

std::vector<RotationState> predict_rotation(RotationLaw law, Law linear, const Scene& scene,
                                            double h, const std::vector<std::int64_t>& recorded) {
  return iterate_rotation(law, linear, scene, h, recorded, start_orientations(scene),
                          start_spins(scene));
}

std::vector<RotationState> predict_rotation_from(RotationLaw law, Law linear, const Scene& scene,
                                                 double h,
                                                 const std::vector<std::int64_t>& recorded,
                                                 const std::vector<RotationState>& start) {
  std::vector<Quat> q0;
  std::vector<VL> w0;
  for (const RotationState& r : start) {
    q0.push_back(r.orientation);
    w0.push_back(r.angular_velocity.cast<LD>());
  }
  return iterate_rotation(law, linear, scene, h, recorded, q0, w0);
}

double rotation_amplification(RotationLaw law, Law linear, const Scene& scene, double h,
                              const std::vector<std::int64_t>& recorded) {
  constexpr LD kNudge = 1e-9L;
  const std::vector<VL> w0 = start_spins(scene);
  const std::vector<Quat> q0 = start_orientations(scene);
  const std::vector<RotationState> base = iterate_rotation(law, linear, scene, h, recorded, q0, w0);
  double worst = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<VL> nudged = w0;
    for (VL& w : nudged) w[axis] += kNudge * std::max(w.norm(), LD(1));
    const std::vector<RotationState> other =
        iterate_rotation(law, linear, scene, h, recorded, q0, nudged);
    for (std::size_t i = 0; i < base.size(); ++i) {
      const double scale = std::max(double(w0[i % w0.size()].norm()), 1.0);
      const double angle = geodesic_angle(base[i].orientation, other[i].orientation);
      const double w = (base[i].angular_velocity - other[i].angular_velocity).norm() / scale;
      worst = std::max(worst, std::max(angle, w) / double(kNudge));
    }
  }
  return worst;
}

double predicted_momentum_drift(const Scene& scene, RotationLaw law, double h, std::size_t body) {
  const std::int64_t steps = step_count(scene, h);
  std::vector<std::int64_t> recorded(static_cast<std::size_t>(steps) + 1);
  for (std::int64_t n = 0; n <= steps; ++n) recorded[static_cast<std::size_t>(n)] = n;
  const std::vector<RotationState> states =
      predict_rotation(law, DampingOrder::AfterForces, scene, h, recorded);
  const Vec3 I = inertia_of(scene.bodies[body]);
  std::vector<Vec3> L;
  for (std::size_t s = body; s < states.size(); s += scene.bodies.size())
    L.push_back(world_momentum(states[s].orientation, states[s].angular_velocity, I));
  return momentum_drift(L);
}

RotationResidual rotation_residual(const Trajectory& run, std::span<const RotationState> predicted,
                                   std::size_t samples) {
  const auto not_nan = [](double d) { return std::isnan(d) ? INFINITY : d; };
  RotationResidual r;
  for (const RotationState& p : predicted)
    r.w_scale = std::max(r.w_scale, not_nan(p.angular_velocity.norm()));
  double worst = -1.0;
  for (std::size_t s = 0; s < std::min(samples, run.samples()); ++s) {
    for (std::size_t b = 0; b < run.bodies(); ++b) {
      const RotationState& got = run.rotation_at(s, b);
      const RotationState& law = predicted[s * run.bodies() + b];
      const double angle = not_nan(geodesic_angle(got.orientation, law.orientation));
      const double w = not_nan((got.angular_velocity - law.angular_velocity).norm());
      r.angle = std::max(r.angle, angle);
      r.w = std::max(r.w, w);
      const double score = std::max(angle, r.w_scale > 0.0 ? w / r.w_scale : w);
      if (score > worst) worst = score, r.worst_sample = s, r.worst_body = b;
    }
  }
  return r;
}

}  // namespace dropcheck
