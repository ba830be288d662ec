#include "harness/judge/own_law.hpp"

#include <algorithm>
#include <cmath>

#include "harness/core/number_format.hpp"
#include "harness/judge/attribution.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/oracles/own_arithmetic.hpp"
#include "harness/oracles/own_rotation.hpp"

namespace dropcheck {
namespace {

struct Scales {
  double x = 0.0, v = 0.0;
};

// |a|, without overflow for finite components: norm() squares them (a state at 1e200 m has a
// finite position and an infinite norm), so it falls back to Eigen's scaled stableNorm() there.
double length(const Vec3& a) {
  const double n = a.norm();
  return std::isinf(n) && a.allFinite() ? a.stableNorm() : n;
}

// The largest |x| and |v| the law reaches. A non-finite state makes its scale NaN (std::max would
// skip a NaN and keep the finite part: a law that left finite values must not look finite).
Scales scales(const Trajectory& law) {
  Scales s;
  for (const BodyState& b : law.states) {
    const double x = length(b.position), v = length(b.velocity);
    if (!std::isfinite(x) || !std::isfinite(v)) return {NAN, NAN};
    s.x = std::max(s.x, x);
    s.v = std::max(s.v, v);
  }
  return s;
}

OwnLawTolerance tolerance_for(Scalar scalar, bool copied, const Trajectory& law) {
  const Scales s = scales(law);
  const double ulps =
      copied ? tolerance::kCopiedUlps
             : tolerance::kStepUlps * static_cast<double>(std::max<std::int64_t>(law.steps, 1));
  // One scale for positions and velocities: the largest magnitude the run carries (a body at rest
  // still rounds its position, a body near the origin its velocity).
  const double scale = std::max(s.x, s.v);
  OwnLawTolerance t{
      ulps * machine_epsilon(scalar) * scale, ulps * machine_epsilon(scalar) * scale, {}};
  if (!t.finite()) {
    t.rule = "none: the law reaches Inf or NaN within the steps compared";
    return t;
  }
  t.rule = g3(ulps) + " ulps of " + g3(scale) + " (" + to_string(scalar) +
           (copied ? ", operation order copied)"
                   : ", order not copied: " + g3(tolerance::kStepUlps) + " ulps per step)");
  return t;
}

// The error-controlled member's budget. Its integrator keeps each step's error estimate, a
// root-mean-square over the coordinates weighted as Simbody weights them (IntegratorRep.h,
// calcErrorNorm and calcRelativeScaling), at most the accuracy a: with n_q coordinates (7 per free
// body: position and quaternion) in metres, and n_u speeds (6) relative to max(|u|, 1), one step
// moves a position by at most sqrt(n_q)*a m and a velocity by sqrt(n_u)*a*max(|v|, 1) m/s. Over N
// steps in a run of T s, a velocity's share carried into the position included:
//   x: N*a*(sqrt(n_q) + sqrt(n_u)*max(|v|, 1)*T),   v: N*a*sqrt(n_u)*max(|v|, 1)
// (drag only shrinks an error; the member runs no spring, Engine::cannot_run). N is the engine's
// own step count, at least the run's. Measured: free_fall_drag at h = 1/60 and a = 1e-3 is met to
// 5.6e-10 m, against a budget of 1.01 m; at a = 1e-10 and h = 0.1 (44 steps), 2.5e-9 m against
// 7.3e-8 m.
OwnLawTolerance accuracy_budget(const EngineInfo& info, const Trajectory& law,
                                std::int64_t engine_steps) {
  const Scales s = scales(law);
  // Every body counted (a static one has no coordinates in Simbody: the budget errs loose).
  const double bodies = static_cast<double>(law.bodies());
  const double nq = 7.0 * bodies, nu = 6.0 * bodies;
  const double steps = static_cast<double>(std::max(engine_steps, law.steps));
  const double duration = static_cast<double>(law.steps) * law.h;
  const double speed = std::max(s.v, 1.0);
  const double a = info.accuracy;
  OwnLawTolerance t{steps * a * (std::sqrt(nq) + std::sqrt(nu) * speed * duration),
                    steps * a * std::sqrt(nu) * speed,
                    {}};
  t.rule = "accuracy " + g3(a) + " per step over " + g3(steps) +
           " engine steps (error-controlled: the continuous model, met within its accuracy)";
  if (!t.finite()) t.rule = "none: the model reaches Inf or NaN within the steps compared";
  return t;
}

double not_nan(double d) {
  return std::isnan(d) ? INFINITY : d;
}

// The rotational part of the verdict: `run` against `own`'s rotation over the samples compared.
// Tolerance: ulps of the scalar per step (kCopiedUlps in all when ours's order is copied), times
// the law's amplification (rounding injected early grows as the law amplifies any change), of 1
// rad for the angle and of the largest |w| for the angular velocity.
void judge_rotation(const EngineInfo& info, const Trajectory& run, const Trajectory& own,
                    std::size_t samples, OwnLawVerdict& r) {
  r.rotation = true;
  r.rotation_law = to_string(info.rotation_law);
  const bool copied = info.arithmetic == DampingForm::phi_multiply;
  const double steps = static_cast<double>(std::max<std::int64_t>(own.steps, 1));
  const double ulps =
      copied ? tolerance::kCopiedUlps : (tolerance::kStepUlps + own.rotation_step_ulps) * steps;
  const RotationResidual d = rotation_residual(run, own.rotations, samples);
  r.residual_angle = d.angle;
  r.residual_w = d.w;
  r.tolerance_angle = ulps * machine_epsilon(info.scalar) * own.amplification;
  // A spatial bias turns even a body its law never turns: its ulps count from 1 rad/s at least.
  r.tolerance_w =
      r.tolerance_angle * (own.rotation_step_ulps > 0.0 ? std::max(d.w_scale, 1.0) : d.w_scale);
  r.rotation_rule = g3(ulps) + " ulps x amplification " + g3(own.amplification) + " (" +
                    to_string(info.scalar) +
                    (copied ? ", operation order copied)"
                            : ", order not copied: " + g3(tolerance::kStepUlps) + " ulps per step" +
                                  (own.rotation_step_ulps > 0.0
                                       ? " + " + g3(own.rotation_step_ulps) +
                                             " for its spatial bias v x m*v, 2*eps*m*|v|^2*h/I_min)"
                                       : std::string(")")));
}

}  // namespace

OwnLawTolerance own_law_tolerance(const EngineInfo& info, const Trajectory& own_law,
                                  std::int64_t engine_steps) {
  if (info.law.scheme == Scheme::ErrorControlled)
    return accuracy_budget(info, own_law, engine_steps);
  return tolerance_for(info.scalar, order_copied(info), own_law);
}

Trajectory before_step(const Trajectory& t, std::int64_t n) {
  if (n < 0) return t;
  Trajectory out = t;
  std::size_t keep = 0;
  while (keep < t.samples() && t.recorded[keep] < n) ++keep;
  out.recorded.resize(keep);
  out.states.resize(keep * t.bodies());
  if (t.rotates) out.rotations.resize(keep * t.bodies());
  return out;
}

bool OwnLawTolerance::finite() const {
  return std::isfinite(x) && std::isfinite(v);
}

bool OwnLawVerdict::rotation_judged() const {
  return std::isfinite(tolerance_angle) && std::isfinite(tolerance_w) &&
         tolerance_angle <= tolerance::kMaxRotationTolerance;
}

bool OwnLawVerdict::follows() const {
  if (!failure.empty() || !tolerance.finite() || residual_x > tolerance.x ||
      residual_v > tolerance.v)
    return false;
  if (!rotation) return true;
  if (!std::isfinite(tolerance_angle) || !std::isfinite(tolerance_w)) return false;
  return !rotation_judged() || (residual_angle <= tolerance_angle && residual_w <= tolerance_w);
}

OwnLawVerdict judge_own_law(const EngineInfo& info, const Trajectory& run, const Trajectory& own,
                            const Trajectory& exact) {
  OwnLawVerdict r;
  r.engine = info.name;
  r.law = to_string(info.law);
  r.tolerance = own_law_tolerance(info, own, run.engine_steps);
  if (run.status != RunStatus::ok)
    r.failure = std::string(to_string(run.status)) + ": " + run.failure;
  else if (own.status != RunStatus::ok)
    r.failure = "its law: " + own.failure;
  r.clamped_from = run.first_clamped_step;
  const std::size_t n = std::min({run.samples(), own.samples(), exact.samples()});
  double worst = -1.0;
  for (std::size_t s = 0; s < n; ++s) {
    if (r.clamped_from >= 0 && run.recorded[s] >= r.clamped_from) break;
    r.compared_steps = run.recorded[s];
    for (std::size_t b = 0; b < run.bodies(); ++b) {
      // A NaN distance counts as infinite (std::max would skip it).
      const double dx = not_nan((run.at(s, b).position - own.at(s, b).position).norm());
      const double dv = not_nan((run.at(s, b).velocity - own.at(s, b).velocity).norm());
      r.residual_x = std::max(r.residual_x, dx);
      r.residual_v = std::max(r.residual_v, dv);
      r.precision = std::max(r.precision, (own.at(s, b).position - exact.at(s, b).position).norm());
      const double rel =
          std::max(dx / std::max(r.tolerance.x, 1e-300), dv / std::max(r.tolerance.v, 1e-300));
      if (rel > worst) worst = rel, r.worst_sample = s, r.worst_body = b;
    }
  }
  if (run.rotates && own.rotates) {
    std::size_t compared = 0;
    while (compared < n && (r.clamped_from < 0 || run.recorded[compared] < r.clamped_from))
      ++compared;
    judge_rotation(info, run, own, compared, r);
  }
  return r;
}

OwnLawVerdict judge_own_law(const EngineInfo& info, const Scene& scene, const Trajectory& run) {
  return judge_own_law(info, run, predict_own_arithmetic(info, scene, run.h),
                       predict_discrete(info.law, scene, run.h));
}

std::string OwnLawVerdict::sentence() const {
  const std::string bound =
      tolerance.finite() ? g3(tolerance.x) + " m, " + g3(tolerance.v) + " m/s: " + tolerance.rule
                         : "NONE: no departure can be bounded";
  std::string s = "max |x - law| " + g3(residual_x) + " m, |v - law| " + g3(residual_v) +
                  " m/s (tolerance " + bound + "; law " + law + ")";
  if (!tolerance.finite())
    s += "; TOLERANCE NOT FINITE: the law reaches Inf or NaN within the steps compared (a stable "
         "law never does; an unstable one is judged only while finite)";
  s += "; precision part " + format_length(precision) + " (own arithmetic vs long-double law)";
  if (rotation && !std::isfinite(tolerance_angle + tolerance_w))
    s += "; rotation: NO TOLERANCE, its law reaches Inf or NaN (law " + rotation_law + ")";
  else if (rotation && !rotation_judged())
    s += "; rotation: not judged at this step: the law amplifies rounding to " +
         g3(tolerance_angle) + " rad (" + rotation_rule + "), more than " +
         g3(tolerance::kMaxRotationTolerance) + " rad; max angle to law " + g3(residual_angle) +
         " rad";
  else if (rotation)
    s += "; rotation: max angle to law " + g3(residual_angle) + " rad, |w - law| " +
         g3(residual_w) + " rad/s (tolerance " + g3(tolerance_angle) + " rad, " + g3(tolerance_w) +
         " rad/s: " + rotation_rule + "; law " + rotation_law + ")";
  if (clamped_from >= 0)
    s += "; the engine clamped a speed at step " + std::to_string(clamped_from) +
         " (clamp, reported by the engine): compared up to step " + std::to_string(compared_steps);
  if (!failure.empty()) s += "; run failed: " + failure;
  return s;
}

std::string law_family_name(Law law) {
  if (law.scheme == Scheme::RK4) return "fourth-order Runge-Kutta, damping as a force (Wild Magic)";
  if (law.scheme == Scheme::ErrorControlled)
    return "error-controlled variable step, damping as a force (Simbody's Runge-Kutta-Merson)";
  const bool explicit_x = law.position == PositionUpdate::Explicit;
  std::string name = explicit_x ? "explicit Euler" : "semi-implicit Euler";
  switch (law.damping) {
    case DampingOrder::AfterForces:
      return name + (explicit_x ? ", damping after the forces"
                                : ", damping after the forces (ours, Box2D, MuJoCo)");
    case DampingOrder::BeforeForces:
      return name + ", damping before the forces (Bullet's order)";
    case DampingOrder::AfterPosition:
      return name + ", damping after the position update (ODE's order)";
  }
  return name;
}

std::optional<Law> fitting_law(const EngineInfo& info, const Scene& scene, const Trajectory& run) {
  if (run.status != RunStatus::ok) return std::nullopt;
  for (const Law& law : kLawFamily) {
    EngineInfo as = info;
    as.law = law;
    as.arithmetic = DampingForm::other;  // any order: the long-double law, per-step ulps
    const Trajectory exact = predict_discrete(law, scene, run.h);
    Trajectory unclamped = run;
    unclamped.first_clamped_step = -1;
    if (judge_own_law(as, unclamped, exact, exact).follows()) return law;
  }
  return std::nullopt;
}

}  // namespace dropcheck
