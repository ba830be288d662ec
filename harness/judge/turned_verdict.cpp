#include "harness/judge/turned_verdict.hpp"

#include <algorithm>
#include <limits>

#include "harness/core/number_format.hpp"
#include "harness/core/rotation_metrics.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/oracles/turned_contact_step.hpp"

namespace dropcheck {
namespace {

TurnedResidual residual(const Trajectory& run, std::size_t sample, const TurnedCandidate& c) {
  TurnedResidual r;
  for (std::size_t b = 0; b < run.bodies(); ++b) {
    const BodyState& s = run.at(sample, b);
    const RotationState& q = run.rotation_at(sample, b);
    r.position = std::max(r.position, (s.position - c.linear[b].position).norm());
    r.velocity = std::max(r.velocity, (s.velocity - c.linear[b].velocity).norm());
    r.angle = std::max(r.angle, geodesic_angle(q.orientation, c.rotation[b].orientation));
    r.spin = std::max(r.spin, (q.angular_velocity - c.rotation[b].angular_velocity).norm());
  }
  return r;
}

// The quantity of `r` furthest over its tolerance.
const char* worst_quantity(const TurnedResidual& r, const TurnedResidual& t) {
  const double q[4] = {r.position / t.position, r.velocity / t.velocity, r.angle / t.angle,
                       r.spin / t.spin};
  static const char* names[4] = {"position", "velocity", "orientation", "angular velocity"};
  return names[std::max_element(q, q + 4) - q];
}

// The step's tolerance: kTurnedStepUlps units in the last place of the scalar, of each quantity's
// size in the law's state (at least 1 m, 1 m/s, 1 rad, 1 rad/s): |x|, |v|, the turn |w|*h and |w|.
// A step's rounding scales with the terms it adds, and a turn of |w|*h rad rounds like that angle.
TurnedResidual step_tolerance(const TurnedCandidate& c, double h, double ulp) {
  double x = 1.0, v = 1.0, turn = 1.0, w = 1.0;
  for (std::size_t b = 0; b < c.linear.size(); ++b) {
    x = std::max(x, c.linear[b].position.norm());
    v = std::max(v, c.linear[b].velocity.norm());
    turn = std::max(turn, c.rotation[b].angular_velocity.norm() * h);
    w = std::max(w, c.rotation[b].angular_velocity.norm());
  }
  const double k = tolerance::kTurnedStepUlps * ulp;
  return {k * x, k * v, k * turn, k * w};
}

std::string residual_text(const TurnedResidual& r) {
  return printf_string("|dx| %.2g m, |dv| %.2g m/s, %.2g rad, |dw| %.2g rad/s", r.position,
                       r.velocity, r.angle, r.spin);
}

}  // namespace

double TurnedResidual::ratio(const TurnedResidual& t) const {
  return std::max({position / t.position, velocity / t.velocity, angle / t.angle, spin / t.spin});
}

TurnedVerdict judge_turned_contact(const Scene& scene, const EngineInfo& info,
                                   const Trajectory& run) {
  TurnedVerdict v;
  if (info.turned_contact != TurnedContact::mean_corner) {
    v.not_judged = "the engine declares no turned-box contact law";
    return v;
  }
  if (!run.rotates || !run.keeps_every_step()) {
    v.not_judged = "the run does not keep every step's rotation";
    return v;
  }
  const TurnedContactScope scope = turned_contact_scope(scene, info, run.h);
  if (!scope.not_judged.empty()) {
    v.not_judged = scope.not_judged;
    return v;
  }
  const bool f32 = info.scalar == Scalar::f32;
  const double ulp =
      f32 ? std::numeric_limits<float>::epsilon() : std::numeric_limits<double>::epsilon();
  const double decide = f32 ? tolerance::kTurnedDecideF32 : tolerance::kTurnedDecideF64;
  double worst_ratio = -1.0;
  const std::size_t n = run.bodies();
  for (std::size_t k = 0; k + 1 < run.samples(); ++k) {
    const std::span<const BodyState> linear(&run.at(k, 0), n);
    const std::span<const RotationState> rotation(&run.rotation_at(k, 0), n);
    const std::vector<TurnedCandidate> candidates =
        turned_contact_step(scope.setup, linear, rotation, decide);
    TurnedResidual best, best_tolerance;
    double best_ratio = std::numeric_limits<double>::infinity();
    bool touching = false;
    for (const TurnedCandidate& c : candidates) {
      const TurnedResidual r = residual(run, k + 1, c);
      const TurnedResidual t = step_tolerance(c, run.h, ulp);
      touching = touching || c.contacts > 0;
      if (const double q = r.ratio(t); q < best_ratio) {
        best_ratio = q;
        best = r;
        best_tolerance = t;
      }
    }
    ++v.steps;
    v.contact_steps += touching ? 1 : 0;
    v.undecided_steps += candidates.size() > 1 ? 1 : 0;
    v.worst.position = std::max(v.worst.position, best.position);
    v.worst.velocity = std::max(v.worst.velocity, best.velocity);
    v.worst.angle = std::max(v.worst.angle, best.angle);
    v.worst.spin = std::max(v.worst.spin, best.spin);
    if (!(best_ratio <= worst_ratio)) {
      worst_ratio = best_ratio;
      v.worst_step = run.recorded[k + 1];
      v.tolerance = best_tolerance;
    }
    if (v.first_departure < 0 && !(best_ratio <= 1.0)) {
      v.first_departure = run.recorded[k + 1];
      v.departure_quantity = worst_quantity(best, best_tolerance);
      v.at_departure = best;
      v.tolerance = best_tolerance;
    }
  }
  return v;
}

std::string TurnedVerdict::sentence() const {
  if (!not_judged.empty()) return "turned-box contact law not judged: " + not_judged;
  const std::string counts = printf_string(
      "%lld steps, %lld starting in contact, %lld with a corner within rounding of "
      "the face (both sides tried)",
      static_cast<long long>(steps), static_cast<long long>(contact_steps),
      static_cast<long long>(undecided_steps));
  if (first_departure < 0)
    return "follows its turned-box contact law (" + describe(TurnedContact::mean_corner) +
           ") at every step, each from the run's state the step before: " + counts + "; worst " +
           residual_text(worst) + " (tolerance " + residual_text(tolerance) + ")";
  return "DEPARTS at step " + std::to_string(first_departure) + ": " + departure_quantity +
         " off, " + residual_text(at_departure) + " from its turned-box contact law's step (" +
         describe(TurnedContact::mean_corner) + ") taken from the run's own state (tolerance " +
         residual_text(tolerance) + "); " + counts;
}

}  // namespace dropcheck
