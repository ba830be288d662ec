#include "harness/judge/law_stability.hpp"

#include <cmath>
#include <cstdio>

#include "harness/core/number_format.hpp"
#include "harness/judge/stability_classify.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/oracles/own_arithmetic.hpp"
#include "harness/oracles/own_rotation.hpp"
#include "harness/oracles/stability_theory.hpp"

namespace dropcheck {
namespace {

std::string g(double v) {
  return sig(v, 4);
}

// The damping the edge depends on besides the spring: " with k = 20 1/s and a dashpot of 6 1/s".
std::string damping_text(const SpringModel& s) {
  std::string out;
  if (s.k > 0.0) out += " world damping k = " + g(s.k) + " 1/s";
  if (s.gamma > 0.0)
    out += std::string(out.empty() ? "" : " and") + " dashpot C/m = " + g(s.gamma) + " 1/s";
  return out.empty() ? "" : "; with" + out;
}

// Finite and sane: |x|^2 and |v|^2 finite, as the distances and tolerances computed from them must
// be (a double law reaching 1e155 m is finite, but its squared norm, hence its norm, is Inf).
bool finite(const BodyState& b) {
  return std::isfinite(b.position.squaredNorm()) && std::isfinite(b.velocity.squaredNorm());
}

// The first recorded step with a state that is not finite and sane in `t`; -1 when none.
std::int64_t first_non_finite(const Trajectory& t) {
  for (std::size_t s = 0; s < t.samples(); ++s)
    for (std::size_t b = 0; b < t.bodies(); ++b)
      if (!finite(t.at(s, b))) return t.recorded[s];
  return -1;
}

// The RK4 member never renormalises q (rotation_law.hpp): on a spin of |w| each step scales |q| by
// |R(i*|w|*h/2)| = sqrt(1 - x^6/72 + x^8/576), x = |w|*h/2, below 1. "" while every body's |q|
// stays within the unit band (kUnitSlack) over the run; otherwise where the law leaves it.
std::string rk4_orientation_limit(const Scene& scene, const Timestep& h) {
  const std::int64_t steps = step_count(scene, h.seconds);
  std::vector<std::int64_t> recorded(static_cast<std::size_t>(steps) + 1);
  for (std::int64_t n = 0; n <= steps; ++n) recorded[static_cast<std::size_t>(n)] = n;
  const std::vector<RotationState> law =
      predict_rotation(kRotationRk4, kRungeKutta4, scene, h.seconds, recorded);
  const std::size_t bodies = scene.bodies.size();
  for (std::size_t i = 0; i < law.size(); ++i) {
    const double n2 = law[i].orientation.squaredNorm();
    if (n2 >= kUnitNorm2Min && n2 <= kUnitNorm2Max) continue;
    return "its law (RK4 on the quaternion, never renormalised) takes |q| of '" +
           scene.bodies[i % bodies].name + "' to " + sig(std::sqrt(n2), 6) + " at step " +
           std::to_string(i / bodies) + " (h = " + h.text + "), out of the band 1 -+ " +
           g(kUnitSlack) + " of a rotation";
  }
  return "";
}

}  // namespace

std::string law_instability(const Scene& scene, Law law, const Timestep& h) {
  if (law.scheme == Scheme::RK4 && needs_rotation(scene))
    if (std::string limit = rk4_orientation_limit(scene, h); !limit.empty()) return limit;
  const double k = scene.world.damping_rate;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].is_static) continue;
    const std::optional<SpringModel> s = body_spring(scene, i);
    if (!s && !damping_step_stable(law, k, h.seconds))
      return "its law (" + law_family_name(law) + ") is unstable at h = " + h.text +
             ": k*h = " + g(k * h.seconds) + " > " + g(kRk4DampingEdge) +
             ", where |1 - u + u^2/2 - u^3/6 + u^4/24| passes 1, for '" + scene.bodies[i].name +
             "'";
    if (!s || spring_step_stable(law, *s, h.seconds)) continue;
    // The edge as omega*h: 2 for an undamped spring under every semi-implicit member; drag and a
    // dashpot move it (stability_theory.cpp). An explicit law has no edge without damping.
    const double edge = spring_max_stable_dt(law, *s);
    const std::string bound = edge > 0.0 && std::isfinite(edge)
                                  ? " > " + g(s->omega * edge) + ", its stability edge"
                                  : ", where it is unstable at every step";
    return "its law (" + law_family_name(law) + ") is unstable at h = " + h.text +
           ": omega*h = " + g(s->omega * h.seconds) + bound + damping_text(*s) +
           ", for the spring on '" + scene.bodies[i].name + "'";
  }
  return "";
}

bool blew_up(const Trajectory& run) {
  return run.status == RunStatus::non_finite || run.status == RunStatus::engine_error ||
         run.status == RunStatus::crashed;
}

OwnLawVerdict judge_while_law_finite(const EngineInfo& info, const Scene& scene,
                                     const Trajectory& run) {
  Trajectory own = predict_own_arithmetic(info, scene, run.h);
  Trajectory exact = predict_discrete(info.law, scene, run.h);
  const std::int64_t end = first_non_finite(own);
  own = before_step(own, end);
  exact = before_step(exact, end);
  exact = before_step(exact, first_non_finite(exact));  // long double overflows later, if at all
  Trajectory stopped = run;  // a failed run's samples end where it stopped (harness/run/runner.hpp)
  stopped.status = RunStatus::ok;
  stopped.failure.clear();
  return judge_own_law(info, stopped, own, exact);
}

}  // namespace dropcheck
