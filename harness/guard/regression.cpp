// Tiers 1 and 2 and the determinism check of the regression guard (tier 3: regression_physics.cpp).
#include "harness/guard/regression.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "harness/core/number_format.hpp"
#include "harness/core/trajectory_hash.hpp"
#include "harness/io/trajectory_io.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {
namespace {

std::string prefix(const Baseline& b, Tier tier) {
  return b.scene + " / " + b.engine + " / " + to_string(tier) + ": ";
}

TierResult result(TierVerdict v, std::string message) {
  return {v, std::move(message)};
}

// The component (of position when `position`, else velocity) that differs most between a and b.
// a - b, except that two equal values (infinities too) or two NaNs differ by 0: the same failed run
// stored twice is identical. A NaN against a number differs by NaN, which every test below counts
// as more than any tolerance, so a NaN never reads as "identical, 0 m".
double gap(double a, double b) {
  return a == b || (std::isnan(a) && std::isnan(b)) ? 0.0 : a - b;
}

Vec3 gaps(const Vec3& a, const Vec3& b) {
  return {gap(a[0], b[0]), gap(a[1], b[1]), gap(a[2], b[2])};
}

bool over(double difference, double tolerance) {
  return std::isnan(difference) || difference > tolerance;
}

void worst_component(const BodyState& a, const BodyState& b, bool position, SampleDiff& d) {
  static const char* const kNames[2][3] = {{"vx", "vy", "vz"}, {"x", "y", "z"}};
  const Vec3& va = position ? a.position : a.velocity;
  const Vec3& vb = position ? b.position : b.velocity;
  const Vec3 g = gaps(va, vb).cwiseAbs();
  int worst = 0;
  for (int i = 1; i < 3; ++i)
    if (!std::isnan(g[worst]) && over(g[i], g[worst])) worst = i;
  d.component = kNames[position ? 1 : 0][worst];
  d.before = va[worst];
  d.after = vb[worst];
}

std::string structure_problem(const Trajectory& a, const Trajectory& b) {
  if (a.body_names != b.body_names) return "the bodies differ";
  if (a.recorded != b.recorded)
    return "the recorded steps differ (" + std::to_string(a.samples()) + " samples, last step " +
           std::to_string(a.recorded.empty() ? -1 : a.recorded.back()) + " before; " +
           std::to_string(b.samples()) + ", last step " +
           std::to_string(b.recorded.empty() ? -1 : b.recorded.back()) + " now)";
  return {};
}

// "body 'cube' first differs at step 10: y = A in the baseline, B now (|dx| = D m > T m)"
std::string first_difference_text(const SampleDiff& d, double tolerance, std::int64_t every) {
  const bool pos = d.component[0] != 'v';
  return "body '" + d.first_body + "' first differs at step " + std::to_string(d.first_step) +
         " (samples every " + std::to_string(every) + " steps): " + d.component + " = " +
         exact(d.before) + " in the baseline, " + exact(d.after) + " now, " +
         (pos ? "|dx| = " : "|dv| = ") + g3(d.first_delta) + (pos ? " m" : " m/s") + " > " +
         g3(tolerance) + (pos ? " m" : " m/s") + "; max |dx| " + g3(d.max_dx) + " m (body '" +
         d.max_body + "', step " + std::to_string(d.max_step) + ")";
}

// Sweep errors against oracle 1, per h: |now - baseline| within the tolerance.
std::string sweep_problem(const Baseline& expected, const Baseline& now, double tolerance) {
  if (expected.sweep.size() != now.sweep.size()) return "the sweep has a different number of steps";
  for (std::size_t i = 0; i < now.sweep.size(); ++i) {
    const SweepPoint& a = expected.sweep[i];
    const SweepPoint& b = now.sweep[i];
    if (a.dt.text != b.dt.text || a.steps != b.steps) return "the sweep's steps differ";
    if (a.status != b.status)
      return "at h = " + a.dt.text + " the run was " + a.status + ", now " + b.status;
    const double d = std::abs(a.analytic_max_dx - b.analytic_max_dx);
    if (d > tolerance)
      return "at h = " + a.dt.text + " max |dx| against the analytic solution moved from " +
             exact(a.analytic_max_dx) + " to " + exact(b.analytic_max_dx) + " m (by " + g3(d) +
             " m)";
  }
  return {};
}

}  // namespace

double regression_tolerance(Scalar scalar) {
  // harness/judge/tolerances.hpp has the measurements behind both values.
  return scalar == Scalar::f32 ? tolerance::kRegressionF32 : tolerance::kRegressionF64;
}

SampleDiff diff_samples(const Trajectory& before, const Trajectory& after, double tolerance) {
  SampleDiff d;
  d.incomparable = structure_problem(before, after);
  if (!d.incomparable.empty()) return d;
  for (std::size_t s = 0; s < before.samples(); ++s) {
    for (std::size_t b = 0; b < before.bodies(); ++b) {
      const BodyState& x = before.at(s, b);
      const BodyState& y = after.at(s, b);
      const double dx = gaps(x.position, y.position).norm();
      const double dv = gaps(x.velocity, y.velocity).norm();
      if (d.max_step < 0 || (!std::isnan(d.max_dx) && over(dx, d.max_dx))) {
        d.max_dx = dx;
        d.max_step = before.recorded[s];
        d.max_body = before.body_names[b];
      }
      if (d.first_step >= 0 || (!over(dx, tolerance) && !over(dv, tolerance))) continue;
      d.first_step = before.recorded[s];
      d.first_body = before.body_names[b];
      d.first_delta = over(dx, tolerance) ? dx : dv;
      worst_component(x, y, over(dx, tolerance), d);
    }
  }
  return d;
}

TierResult check_bits(const Baseline& expected, const Baseline& now) {
  const std::string p = prefix(now, Tier::bits);
  if (!now.skipped.empty())
    return result(TierVerdict::skipped, p + "the engine cannot run this scene: " + now.skipped);
  const std::vector<std::string>& known = expected.build_keys;
  if (now.build_keys.empty() || known.empty())
    return result(TierVerdict::skipped,
                  p + (known.empty() ? "the baseline" : "this run") +
                      " names no build; bits may differ, tier 2 compares at tolerance");
  const std::string& key = now.build_keys.front();
  if (std::find(known.begin(), known.end(), key) == known.end())
    return result(TierVerdict::skipped, p + "the baseline was made by [" +
                                            fmt::format("{}", fmt::join(known, "] and [")) +
                                            "], this build is [" + key +
                                            "]; bits may differ, tier 2 compares at tolerance");
  if (expected.hash == now.hash && expected.status == now.status)
    return result(TierVerdict::passed, p + "hash " + now.hash + " identical to the baseline's");
  const SampleDiff d = diff_samples(expected.samples, now.samples, 0.0);
  std::string where = !d.incomparable.empty() ? d.incomparable
                      : d.first_step >= 0     ? first_difference_text(d, 0.0, now.record_every)
                      : now.samples.rotates
                          ? "positions and velocities are identical at every sampled step: the "
                            "change is in the rotation (the hash covers it) or between samples"
                          : "every sampled step is identical; the change lies between samples";
  return result(TierVerdict::failed, p + "hash " + now.hash + " != baseline " + expected.hash +
                                         " on the same build key [" + key + "]: " + where);
}

TierResult check_tolerance(const Baseline& expected, const Baseline& now) {
  const std::string p = prefix(now, Tier::tolerance);
  if (!now.skipped.empty())
    return result(TierVerdict::skipped, p + "the engine cannot run this scene: " + now.skipped);
  if (!expected.skipped.empty())
    return result(TierVerdict::failed,
                  p + "the baseline says skipped (" + expected.skipped + ") but it ran now");
  const double tol = regression_tolerance(now.scalar);
  if (expected.status != now.status)
    return result(TierVerdict::failed,
                  p + "the run was '" + expected.status + "', now '" + now.status + "'");
  const SampleDiff d = diff_samples(expected.samples, now.samples, tol);
  if (!d.incomparable.empty()) return result(TierVerdict::failed, p + d.incomparable);
  if (d.first_step >= 0)
    return result(TierVerdict::failed, p + first_difference_text(d, tol, now.record_every));
  if (std::string s = sweep_problem(expected, now, tol); !s.empty())
    return result(TierVerdict::failed, p + s);
  return result(TierVerdict::passed, p + "max |dx| " + g3(d.max_dx) + " m over " +
                                         std::to_string(now.samples.samples()) +
                                         " samples (tolerance " + g3(tol) + " m for " +
                                         to_string(now.scalar) + ")");
}

TierResult check_determinism(const Scene& scene, const EngineFactory& make) {
  std::unique_ptr<Engine> first = make();
  const std::string p = scene.name + " / " + first->info().name + " / determinism: ";
  if (std::string why = first->cannot_run(scene); !why.empty())
    return result(TierVerdict::skipped, p + "the engine cannot run this scene: " + why);
  const Trajectory a = run_scene(*first, scene, scene.timestep.seconds);
  const Trajectory b = run_scene(*make(), scene, scene.timestep.seconds);
  const std::string csv_a = trajectories_to_csv({&a, 1}), csv_b = trajectories_to_csv({&b, 1});
  const std::string hash_a = trajectory_hash_hex(a), hash_b = trajectory_hash_hex(b);
  if (csv_a == csv_b && hash_a == hash_b)
    return result(TierVerdict::passed, p + "two runs gave identical CSV (" +
                                           std::to_string(csv_a.size()) + " bytes) and hash " +
                                           hash_a);
  std::size_t i = 0;
  while (i < csv_a.size() && i < csv_b.size() && csv_a[i] == csv_b[i]) ++i;
  const std::size_t line_start = csv_a.rfind('\n', i) + 1;
  return result(TierVerdict::failed,
                p + "two runs differ (hash " + hash_a + " vs " + hash_b +
                    "); first differing CSV line: '" +
                    csv_a.substr(line_start, csv_a.find('\n', i) - line_start) + "' vs '" +
                    csv_b.substr(line_start, csv_b.find('\n', i) - line_start) + "'");
}

const char* to_string(Tier tier) {
  switch (tier) {
    case Tier::bits:
      return "bits";
    case Tier::tolerance:
      return "tolerance";
    case Tier::physics:
      return "physics";
    case Tier::determinism:
      return "determinism";
  }
  return "?";
}

std::optional<Tier> parse_tier(const std::string& name) {
  for (Tier t : {Tier::bits, Tier::tolerance, Tier::physics, Tier::determinism})
    if (name == to_string(t)) return t;
  return std::nullopt;
}

const char* to_string(TierVerdict verdict) {
  switch (verdict) {
    case TierVerdict::passed:
      return "passed";
    case TierVerdict::failed:
      return "FAILED";
    case TierVerdict::skipped:
      return "skipped";
  }
  return "?";
}

}  // namespace dropcheck
