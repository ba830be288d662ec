// Tier 3 of the regression guard: a fresh run against the two oracles, whatever the baseline says.
//
// Oracle 2 (own discrete law, harness/judge/own_law.hpp): at every h of the sweep the run follows
// the law its engine declares, within its own-law tolerance. When it does not, the verdict names
// what the run does instead: a member of the law family (a consistent new scheme: declare it), or
// nothing (an inconsistent scheme: its error against the analytic solution stops shrinking).
// Oracle 1 (analytic, harness/oracles/analytic.hpp): every member of the family has a global error
// e(h) = C*h + O(h^2), so p = log2(e(h)/e(h/2)) -> 1 (tolerance::kFirstOrderLow..High).
#include "harness/guard/regression_physics.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "harness/core/number_format.hpp"
#include "harness/guard/regression.hpp"
#include "harness/judge/metrics.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/study/sweep.hpp"

namespace dropcheck {
namespace {

// Oracle 1 over the sweep (largest step first); nullopt without a closed form.
std::optional<OrderEstimate> analytic_order(const Baseline& b) {
  if (b.analytic != "closed form" || b.sweep.size() < 2) return std::nullopt;
  std::vector<SweepPoint> pts = b.sweep;
  std::sort(pts.begin(), pts.end(),
            [](const SweepPoint& x, const SweepPoint& y) { return x.dt.seconds > y.dt.seconds; });
  std::vector<double> h, e;
  double noise = 0.0;
  for (const SweepPoint& p : pts) {
    h.push_back(p.dt.seconds);
    e.push_back(p.analytic_max_dx);
    noise = std::max(noise, p.own_law ? p.own_law->tolerance.x : tolerance::kRegressionF64);
  }
  return estimate_order(h, e, tolerance::kOrderMeasurableFactor * noise);
}

// How far the run at the scene's step is from `baseline`: "differs from the baseline by 3.2 cm at
// h = 1/60" (largest |dx| over the stored samples and bodies), or why it cannot say.
std::string distance(const Baseline& now, const Baseline* baseline) {
  if (!baseline) return "no baseline to compare with";
  const SampleDiff d =
      diff_samples(baseline->samples, now.samples, regression_tolerance(now.scalar));
  if (!d.incomparable.empty()) return "not comparable with the baseline: " + d.incomparable;
  return "differs from the baseline by " + format_length(d.max_dx) + " at h = " + now.dt.text;
}

// What the run does instead of its declared law: the cause of an oracle-2 failure.
std::string departure_cause(const Baseline& b, const SweepPoint& p, const Baseline* baseline) {
  const std::optional<OrderEstimate> o = analytic_order(b);
  const std::string orders =
      o ? "observed orders" +
              [&] {
                std::string s;
                for (double x : o->orders)
                  s += std::isfinite(x) ? " " + g3(x) : std::string(" undefined");
                return s;
              }()
        : "order not measured (no closed form)";
  if (p.fits)
    return "; the run follows another member of the law family instead, a consistent new "
           "scheme: " +
           std::string(o && o->first_order ? "first-order, " : "") + "follows " +
           law_family_name(*p.fits) + " (" + to_string(*p.fits) + "); " + distance(b, baseline) +
           " (" + orders +
           "). If intended, declare that law in the engine's adapter (EngineInfo::law)";
  if (o && !o->consistent) {
    double worst = INFINITY;
    for (double x : o->orders) worst = std::min(worst, x);
    return "; it matches no member of the law family and its error against the analytic solution "
           "does not shrink as h halves: order " +
           g3(worst) + ": not consistent (a broken scheme)";
  }
  return "; it matches no member of the law family (" + orders + ")";
}

// A run whose positions follow its law and whose rotation does not: the rotational update changed.
std::string rotation_problem(const Baseline& b, const SweepPoint& p) {
  const OwnLawVerdict& v = *p.own_law;
  return "oracle 2 (own rotational law: " + v.rotation_law + ") fails: at h = " + p.dt.text +
         " the rotation of " + b.engine + " departs from it by " + g3(v.residual_angle) +
         " rad, |w - law| " + g3(v.residual_w) + " rad/s, beyond its tolerance " +
         g3(v.tolerance_angle) + " rad (" + v.rotation_rule +
         "); positions and velocities follow " + b.law +
         (p.rotation_fits.empty() ? "; its rotation matches no rotational member"
                                  : "; its rotation follows the member " + p.rotation_fits +
                                        " instead. If intended, declare it in the engine's adapter "
                                        "(EngineInfo::rotation_law)");
}

// Oracle 2 at every h; "" when all pass, else the failure.
std::string law_problem(const Baseline& b, const Baseline* baseline, std::string& summary) {
  double worst = 0.0, worst_tol = 0.0;
  std::string worst_h = "-";
  for (const SweepPoint& p : b.sweep) {
    if (p.status != "ok") return "the run at h = " + p.dt.text + " ended with status " + p.status;
    if (!p.own_law) continue;
    const OwnLawVerdict& v = *p.own_law;
    if (!v.follows() && v.rotation && v.residual_x <= v.tolerance.x &&
        v.residual_v <= v.tolerance.v)
      return rotation_problem(b, p);
    if (!p.own_law->follows() || std::isnan(p.law_max_dx))
      return "oracle 2 (own discrete law: " + b.law + ") fails: at h = " + p.dt.text + " body '" +
             p.law_worst_body + "' departs from it by " + g3(p.law_max_dx) + " m, beyond its " +
             "own-law tolerance " + g3(p.own_law->tolerance.x) + " m (" +
             p.own_law->tolerance.rule + ") from step " + std::to_string(p.law_first_over) + " on" +
             departure_cause(b, p, baseline);
    if (p.law_max_dx >= worst)
      worst = p.law_max_dx, worst_h = p.dt.text, worst_tol = p.own_law->tolerance.x;
  }
  summary = "oracle 2 (own law " + b.law + "): max departure " + g3(worst) +
            " m at h = " + worst_h + " (tolerance " + g3(worst_tol) + " m)";
  return {};
}

// Oracle 1: observed order of the max error as h halves; "" when first order or not measurable.
std::string order_problem(const Baseline& b, std::string& summary) {
  const std::optional<OrderEstimate> o = analytic_order(b);
  if (!o) {
    summary = "oracle 1: no closed form (" + b.analytic + ")";
    return {};
  }
  summary = "oracle 1 (analytic): " + o->text;
  if (!o->measurable) {
    summary += ", at rounding level: order not measurable";
    return {};
  }
  if (o->first_order) return {};
  std::vector<SweepPoint> pts = b.sweep;
  std::sort(pts.begin(), pts.end(),
            [](const SweepPoint& x, const SweepPoint& y) { return x.dt.seconds > y.dt.seconds; });
  for (std::size_t i = 0; i < o->orders.size(); ++i) {
    const double p = o->orders[i];
    if (p >= tolerance::kFirstOrderLow && p <= tolerance::kFirstOrderHigh) continue;
    return "oracle 1 (analytic solution) fails: the error should shrink at first order as h halves "
           "(order " +
           g3(tolerance::kFirstOrderLow) + ".." + g3(tolerance::kFirstOrderHigh) + "), observed " +
           g3(p) + " from h = " + pts[i].dt.text + " to " + pts[i + 1].dt.text + " (max |dx| " +
           g3(pts[i].analytic_max_dx) + " -> " + g3(pts[i + 1].analytic_max_dx) + " m)";
  }
  return {};
}

// The tier's verdict when the stored sweep failed with `why`: a pass when every check of the core
// passes (the failure was a limit of the engine's law, which `dropcheck check` names), else `why`.
TierResult ask_core(const std::string& p, const std::string& why, const CoreChecks& core) {
  if (!core) return {TierVerdict::failed, p + why};
  std::string limits;
  for (const CheckResult& r : core()) {
    if (!r.passed) return {TierVerdict::failed, p + why};
    if (!r.limit.empty()) limits += (limits.empty() ? "" : "; ") + r.check + ": " + r.limit;
  }
  return {TierVerdict::passed, p + "the checks of `dropcheck check` pass" +
                                   (limits.empty() ? std::string() : ", with LIMITs: " + limits) +
                                   " (the stored sweep alone fails: " + why + ")"};
}

// A contact scene has no free-flight law to store: its laws (landing, slide, bounce, stack) are
// judged by the checks `dropcheck check` runs, each naming the step and quantity where the run
// leaves its engine's law.
TierResult contact_laws(const std::string& p, const CoreChecks& core) {
  if (!core)
    return {TierVerdict::skipped, p + "a contact scene: its laws are judged by the checks of "
                                      "`dropcheck check`, and no reference engine was given"};
  std::string passed;
  for (const CheckResult& r : core()) {
    if (!r.passed) return {TierVerdict::failed, p + "contact: " + r.check + ": " + r.message};
    passed += (passed.empty() ? "" : "; ") + r.check;
  }
  return {TierVerdict::passed,
          p + "contact: the checks of `dropcheck check` pass (" + passed + ")"};
}

}  // namespace

CoreChecks core_checks(const Scene& scene, const EngineFactory& engine,
                       const EngineFactory& reference) {
  if (!reference) return {};
  return [&scene, engine, reference] { return check_scene(scene, engine, reference); };
}

TierResult check_physics(const Baseline& now, const Baseline* baseline, const CoreChecks& core,
                         bool contacts) {
  const std::string p = now.scene + " / " + now.engine + " / physics: ";
  if (!now.skipped.empty())
    return {TierVerdict::skipped, p + "the engine cannot run this scene: " + now.skipped};
  if (now.status != "ok")
    return ask_core(p, "the run at h = " + now.dt.text + " ended: " + now.status, core);
  if (contacts) return contact_laws(p, core);
  std::string law, order;
  if (std::string why = law_problem(now, baseline, law); !why.empty())
    return ask_core(p, why, core);
  if (std::string why = order_problem(now, order); !why.empty()) return ask_core(p, why, core);
  return {TierVerdict::passed, p + law + "; " + order};
}

}  // namespace dropcheck
