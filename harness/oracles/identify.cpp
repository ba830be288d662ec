#include "harness/oracles/identify.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>

#include "harness/core/forces.hpp"
#include "harness/core/input_error.hpp"

namespace dropcheck {
namespace {

bool after_forces_type(Law law) {
  return law.scheme == Scheme::Euler && law.damping != DampingOrder::BeforeForces;
}

// k*h from an RK4 member's fitted per-step factor: the root of R(u) = phi (harness/core/law.hpp)
// by Newton from -ln(phi), R' = -(1 - u + u^2/2 - u^3/6). R falls monotonically on [0, 1.596]
// (down to 0.27), which covers every damping a trajectory could have been fitted to.
double rk4_step_rate(double phi) {
  double u = phi > 0.0 ? -std::log(phi) : 1.596;
  for (int i = 0; i < 50; ++i) {
    const double slope = -(1.0 - u + u * u / 2.0 - u * u * u / 6.0);
    if (slope == 0.0) break;
    const double next = std::clamp(u - (rk4_decay(u) - phi) / slope, -1.0, 1.596);
    if (next == u) break;
    u = next;
  }
  return u;
}

void require_usable(const Scene& scene, const Trajectory& run) {
  const auto problem = [&](const std::string& what) {
    return InputError(scene.source, 0, "identify", "trajectory of '" + run.engine + "': " + what);
  };
  if (scene.world.contacts) throw problem("needs a free-flight scene (contacts = false)");
  if (run.status != RunStatus::ok)
    throw problem("the run failed at step " + std::to_string(run.failed_step) + ": " + run.failure);
  if (run.body_names.size() != scene.bodies.size())
    throw problem(std::to_string(run.body_names.size()) + " bodies, the scene has " +
                  std::to_string(scene.bodies.size()));
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    if (run.body_names[b] != scene.bodies[b].name)
      throw problem("body " + std::to_string(b + 1) + " is '" + run.body_names[b] +
                    "', the scene's is '" + scene.bodies[b].name + "'");
  if (run.samples() < 4) throw problem("needs at least 3 steps");
  for (std::size_t s = 0; s < run.samples(); ++s)
    if (run.recorded[s] != static_cast<std::int64_t>(s))
      throw problem("step " + std::to_string(s) + " is missing (every step must be recorded)");
  if (std::none_of(scene.bodies.begin(), scene.bodies.end(),
                   [](const Body& b) { return !b.is_static; }))
    throw problem("the scene has no dynamic body");
}

// F/m of every body at every recorded sample (zero for static bodies).
std::vector<Vec3> accelerations_from_forces(const Scene& scene, const Trajectory& run) {
  std::vector<Vec3> out(run.states.size(), Vec3::Zero());
  std::vector<Vec3> forces(run.bodies());
  for (std::size_t s = 0; s < run.samples(); ++s) {
    compute_forces(scene, std::span(run.states).subspan(s * run.bodies(), run.bodies()), forces);
    for (std::size_t b = 0; b < run.bodies(); ++b)
      out[s * run.bodies() + b] = forces[b] / scene.bodies[b].mass;
  }
  return out;
}

// The velocity fit's design is rank-deficient (phi's column is a combination of the constants'
// columns) when every row's regressor is the same per component: the velocities do not change
// (a force-free run, or one at its terminal velocity). Then phi and c are not determined: any phi
// with c = v - phi*v fits. Pivots below this fraction of the largest count as zero.
constexpr double kRankThreshold = 1e-9;

// Least squares for (phi, c) on the velocity sequence, with the forces' share `gain` (1 for the
// Euler members); fills phi, gravity and determined. Undetermined, the replay takes phi = 1 and
// c = the mean change per step (every solution predicts the same velocities; none is reported).
void solve_velocity(const Scene& scene, const Trajectory& run, const std::vector<Vec3>& f,
                    MemberFit& m, double gain) {
  const bool af = after_forces_type(m.law);
  std::size_t dynamic = 0;
  for (const Body& b : scene.bodies) dynamic += b.is_static ? 0 : 1;
  const Eigen::Index rows = static_cast<Eigen::Index>(3 * dynamic * (run.samples() - 1));
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, 4);
  Eigen::VectorXd y(rows);
  Eigen::Index r = 0;
  for (std::size_t s = 0; s + 1 < run.samples(); ++s) {
    for (std::size_t b = 0; b < run.bodies(); ++b) {
      if (scene.bodies[b].is_static) continue;
      const Vec3& v0 = run.at(s, b).velocity;
      const Vec3& v1 = run.at(s + 1, b).velocity;
      const Vec3 hf = gain * run.h * f[s * run.bodies() + b];
      for (int j = 0; j < 3; ++j, ++r) {
        A(r, 0) = af ? v0[j] + hf[j] : v0[j];
        A(r, 1 + j) = 1.0;
        y(r) = af ? v1[j] : v1[j] - hf[j];
      }
    }
  }
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  qr.setThreshold(kRankThreshold);
  m.determined = qr.rank() == 4;
  Eigen::Vector4d theta;
  if (m.determined) {
    theta = qr.solve(y);
  } else {
    theta(0) = 1.0;
    const Eigen::VectorXd change = y - A.col(0);
    for (int j = 0; j < 3; ++j) theta(1 + j) = change(Eigen::seqN(j, rows / 3, 3)).mean();
  }
  m.phi = theta(0);
  const double scale = af ? m.phi * run.h : gain * run.h;
  m.gravity = theta.tail<3>() / scale;
}

// The member's fit. An RK4 member is fitted as before-forces with its force share T(k*h) (law.hpp:
// v' = R*v + h*T*a): T = 1 at first, then from the k*h of the fitted phi, three times (forces held
// at their step-start values: springs make this an estimate, which the residual then judges
// exactly).
void fit_velocity(const Scene& scene, const Trajectory& run, const std::vector<Vec3>& f,
                  MemberFit& m) {
  solve_velocity(scene, run, f, m, 1.0);
  if (m.law.scheme != Scheme::RK4 || !m.determined) return;
  for (int i = 0; i < 3; ++i) solve_velocity(scene, run, f, m, rk4_gain(rk4_step_rate(m.phi)));
}

// Iterates the member from the recorded initial state; fills max_dx and max_dv.
void law_residual(const Scene& scene, const Trajectory& run, MemberFit& m) {
  std::vector<BodyState> state(run.states.begin(),
                               run.states.begin() + static_cast<long>(run.bodies()));
  std::vector<Vec3> forces(run.bodies());
  const auto springs = springs_by_body(scene);
  const double rk4_rate = rk4_step_rate(m.phi) / run.h;
  m.max_dx = m.max_dv = 0.0;
  for (std::size_t s = 1; s < run.samples(); ++s) {
    compute_forces(scene, state, forces);
    for (std::size_t b = 0; b < run.bodies(); ++b) {
      if (scene.bodies[b].is_static) continue;
      const double mass = scene.bodies[b].mass;
      if (m.law.scheme == Scheme::RK4) {
        const BodyState start = state[b];
        const auto a = [&](const Vec3& x, const Vec3& v) -> Vec3 {
          return m.gravity + stage_force(forces[b], springs[b], start, {x, v}) / mass;
        };
        advance_rk4(rk4_rate, run.h, a, state[b].position, state[b].velocity);
      } else {
        advance(m.law, m.phi, run.h, Vec3(m.gravity + forces[b] / mass), state[b].position,
                state[b].velocity);
      }
      const BodyState& got = run.at(s, b);
      m.max_dx = std::max(m.max_dx, (got.position - state[b].position).cwiseAbs().maxCoeff());
      m.max_dv = std::max(m.max_dv, (got.velocity - state[b].velocity).cwiseAbs().maxCoeff());
    }
  }
  if (!std::isfinite(m.max_dx) || !std::isfinite(m.max_dv)) m.max_dx = m.max_dv = INFINITY;
}

}  // namespace

Identification identify_law(const Scene& scene, const Trajectory& run) {
  require_usable(scene, run);
  const std::vector<Vec3> f = accelerations_from_forces(scene, run);
  Identification id;
  for (Law law : kLawFamily) {
    MemberFit m;
    m.law = law;
    fit_velocity(scene, run, f, m);
    law_residual(scene, run, m);
    id.fits.push_back(m);
  }
  std::vector<std::size_t> order(id.fits.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return id.fits[a].max_dx < id.fits[b].max_dx;
  });
  id.best = order[0];
  id.runner_up = order[1];
  const double best = id.fits[id.best].max_dx;
  id.fits_any = best <= kIdentifyTolerance;
  for (std::size_t i : order)
    if (id.fits[i].max_dx <= 2.0 * best + 1e-12) id.tied.push_back(i);
  id.ambiguous = id.tied.size() > 1;
  id.determined =
      std::all_of(id.fits.begin(), id.fits.end(), [](const MemberFit& m) { return m.determined; });
  return id;
}

}  // namespace dropcheck
