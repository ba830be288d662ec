#include "harness/measure/checks.hpp"

#include <cmath>
#include <cstdio>

#include "harness/oracles/analytic.hpp"
#include "harness/measure/attribution.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/oracles/landing.hpp"
#include "harness/measure/metrics.hpp"
#include "harness/core/runner.hpp"
#include "harness/core/timestep.hpp"

namespace dropcheck {
namespace {

std::string fmt(const char* format, double a, double b = 0.0, double c = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b, c);
  return buf;
}

std::string vec(const Vec3& v) { return fmt("(%.17g, %.17g, %.17g)", v.x(), v.y(), v.z()); }

CheckResult result(const Scene& scene, const std::string& engine, const std::string& check) {
  return {scene.name, engine, check, false, {}};
}

// The largest |engine - law| over samples, bodies and components, with where it happened.
struct Worst {
  double dx = 0.0, dv = 0.0;
  std::size_t sample = 0, body = 0;
};

Worst worst_deviation(const Trajectory& run, const Trajectory& law) {
  Worst w;
  for (std::size_t s = 0; s < std::min(run.samples(), law.samples()); ++s) {
    for (std::size_t b = 0; b < run.bodies(); ++b) {
      const double dx = (run.at(s, b).position - law.at(s, b).position).cwiseAbs().maxCoeff();
      const double dv = (run.at(s, b).velocity - law.at(s, b).velocity).cwiseAbs().maxCoeff();
      if (std::max(dx, dv) > std::max(w.dx, w.dv)) w.sample = s, w.body = b;
      w.dx = std::max(w.dx, dx);
      w.dv = std::max(w.dv, dv);
    }
  }
  return w;
}

std::string orders_text(const std::vector<double>& h, const std::vector<double>& e) {
  std::string s = "max |dx| ";
  for (std::size_t i = 0; i < e.size(); ++i) s += (i ? ", " : "") + format_length(e[i]);
  s += " at h = ";
  for (std::size_t i = 0; i < h.size(); ++i) s += (i ? ", " : "") + fmt("%.4g", h[i]);
  s += "; observed orders";
  for (double p : observed_orders(h, e)) s += std::isfinite(p) ? fmt(" %.3f", p) : std::string(" undefined");
  return s;
}

bool first_order(const std::vector<double>& h, const std::vector<double>& e) {
  const std::vector<double> p = observed_orders(h, e);
  for (double x : p)
    if (!(x >= 0.9 && x <= 1.1)) return false;
  return !p.empty();
}

// The sweep to measure an order over: the scene's timesteps, or h, h/2, h/4 when it has one.
std::vector<Timestep> sweep(const Scene& scene) {
  if (scene.timesteps.size() >= 2) return scene.timesteps;
  const double h = scene.timestep.seconds;
  return {scene.timestep, {h / 2, fmt("%.6g", h / 2)}, {h / 4, fmt("%.6g", h / 4)}};
}

}  // namespace

std::vector<Timestep> conformance_steps(const Scene& scene) {
  std::vector<Timestep> out{scene.timestep};
  for (const Timestep& t : sweep(scene))
    if (out.size() < 3 && t.seconds != scene.timestep.seconds) out.push_back(t);
  return out;
}

CheckResult check_own_law(const Scene& scene, const EngineFactory& make, const Timestep& h) {
  std::unique_ptr<Engine> engine = make();
  const EngineInfo info = engine->info();
  CheckResult r = result(scene, info.name, "own law at h = " + h.text);
  const Trajectory run = run_scene(*engine, scene, h.seconds);
  if (run.status != RunStatus::ok) {
    r.message = std::string("run failed: ") + to_string(run.status) + ": " + run.failure;
    return r;
  }
  const Trajectory law = predict_discrete(info.law, scene, h.seconds);
  const Worst w = worst_deviation(run, law);
  const double tol = rounding_budget(info.scalar, law);
  r.passed = w.dx <= tol && w.dv <= tol;
  const BodyState& got = run.at(w.sample, w.body);
  const BodyState& want = law.at(w.sample, w.body);
  r.message = fmt("max |x - law| %.3g m, |v - law| %.3g m/s (tolerance %.2g for ", w.dx, w.dv, tol) +
              to_string(info.scalar) + ", law " + to_string(info.law) + ")";
  if (!r.passed)
    r.message += "; worst at body '" + run.body_names[w.body] + "' step " +
                 std::to_string(run.recorded[w.sample]) + ": engine x = " + vec(got.position) +
                 " v = " + vec(got.velocity) + ", law x = " + vec(want.position) +
                 " v = " + vec(want.velocity);
  return r;
}

CheckResult check_divergence(const Scene& scene, const EngineFactory& make,
                             const EngineFactory& reference) {
  std::unique_ptr<Engine> engine = make(), ref = reference();
  const EngineInfo ei = engine->info(), ri = ref->info();
  const bool is_reference = ei.name == ri.name;
  CheckResult r = result(scene, ei.name, is_reference ? "convergence to analytic" : "divergence from " + ri.name);
  if (is_reference && !analytic_unavailable(scene).empty()) {
    r.passed = true;
    r.message = "no analytic solution (" + analytic_unavailable(scene) + "); nothing to converge to";
    return r;
  }
  std::vector<double> hs, errors;
  for (const Timestep& h : sweep(scene)) {
    const Trajectory run = run_scene(*engine, scene, h.seconds);
    if (run.status != RunStatus::ok) {
      r.message = "run at h = " + h.text + " failed: " + run.failure;
      return r;
    }
    hs.push_back(h.seconds);
    if (is_reference) {
      errors.push_back(compare_worst(run, *analytic_trajectory(scene, h.seconds), scene.tolerance).max_dx);
      continue;
    }
    const Trajectory other = run_scene(*ref, scene, h.seconds);
    const Attribution a = attribute(run, predict_discrete(ei.law, scene, h.seconds), ei.scalar, other,
                                    predict_discrete(ri.law, scene, h.seconds), ri.scalar);
    if (!a.explained()) {
      r.message = "at h = " + h.text + ": " + a.sentence();
      return r;
    }
    errors.push_back(a.law_part > 10 * a.budget ? a.total : 0.0);
  }
  const bool laws_differ = errors.back() > 0.0;
  r.passed = !laws_differ || first_order(hs, errors);
  r.message = laws_differ ? orders_text(hs, errors) + " (expected 0.9-1.1)"
                          : "same discrete law: divergence within rounding at every step";
  return r;
}

CheckResult check_landing(const Scene& scene, const EngineFactory& make, const Timestep& h) {
  std::unique_ptr<Engine> engine = make();
  const EngineInfo info = engine->info();
  CheckResult r = result(scene, info.name, "landing at h = " + h.text);
  const Trajectory run = run_scene(*engine, scene, h.seconds);
  if (run.status != RunStatus::ok) {
    r.message = std::string("run failed: ") + to_string(run.status) + ": " + run.failure;
    return r;
  }
  r.passed = true;
  for (LandingSetup setup : landing_setups(scene)) {
    // An engine whose resting surface sits above the geometry (Box2D's 0.01 m skin) touches the
    // floor there: contact is reaching rest height + rest_offset (+ its tolerance).
    setup.floor_top += std::max(0.0, info.rest_offset + info.rest_tolerance);
    const LandingObservation o = observe_landing(run, setup);
    const std::int64_t law_step = discrete_contact_step(info.law, scene, h.seconds, setup);
    const bool on_time = o.first_contact_step >= 0 && std::abs(o.first_contact_step - law_step) <= 1;
    const double rebound = o.rebound - info.rest_offset;  // above the engine's own rest height
    const bool no_rebound = rebound <= kMaxRebound;
    const bool rests = std::abs(o.rest_offset - info.rest_offset) <= info.rest_tolerance;
    r.passed = r.passed && on_time && no_rebound && rests && o.still;
    r.message += (r.message.empty() ? "" : "; ") + run.body_names[setup.body] + ": " +
                 fmt("first contact at step %.0f (law: step %.0f; continuous t = %.4f s)",
                     double(o.first_contact_step), double(law_step), setup.contact_time) +
                 (on_time ? "" : " MORE THAN ONE STEP OFF") +
                 fmt(", rebound %.3g m above rest (limit %.0e)", rebound, kMaxRebound) +
                 (no_rebound ? "" : " TOO HIGH") +
                 fmt(", rest offset %.3g m (expected %.3g +- %.3g)", o.rest_offset, info.rest_offset,
                     info.rest_tolerance) +
                 (rests ? "" : " OUT OF RANGE") +
                 fmt(", still: max |v| %.3g m/s, range %.3g m over the last 2 s", o.still_speed,
                     o.still_range) +
                 (o.still ? "" : " NOT STILL");
  }
  return r;
}

std::vector<CheckResult> check_scene(const Scene& scene, const EngineFactory& make,
                                     const EngineFactory& reference) {
  std::vector<CheckResult> out;
  if (!make()->cannot_run(scene).empty()) return out;
  if (scene.world.contacts) {
    out.push_back(check_landing(scene, make, scene.timestep));
    return out;
  }
  for (const Timestep& h : conformance_steps(scene)) out.push_back(check_own_law(scene, make, h));
  out.push_back(check_divergence(scene, make, reference));
  return out;
}

}  // namespace dropcheck
