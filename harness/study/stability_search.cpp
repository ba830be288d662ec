// The search for the largest stable step of one engine on one scene, by bisection on h.
//
// A probe runs the scene at h for duration' = ceil(horizon/h)*h (a whole number of steps: the
// scene's own duration need not be a multiple of a candidate h), horizon = min(duration,
// horizon_steps*h0), and classifies the run (classify_run). Stability in h is assumed monotone
// around the edge: below it stable, above it not. Three starts:
//   h0 stable:            double h until a probe fails (or h passes the cap) -> bracket [lo, hi]
//   h0 fails, not frozen: halve h until a probe is stable (at most max_halvings) -> bracket
//   h0 only frozen:       a small-step failure: double h until stable (min_stable_dt, bisected),
//                         then go on doubling as in the first case
// then bisect the bracket geometrically until hi/lo - 1 < rel_tol; max_stable_dt = lo.
#include "harness/study/stability_search.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "harness/core/number_format.hpp"
#include "harness/io/trajectory_io.hpp"
#include "harness/judge/stability_classify.hpp"
#include "harness/judge/stability_contact.hpp"
#include "harness/oracles/contact_laws.hpp"
#include "harness/oracles/stack.hpp"
#include "harness/run/runner.hpp"

namespace dropcheck {
namespace {

// Runs and classifies one candidate step; remembers the severest failure of the last probe.
struct Prober {
  const EngineFactory& make;
  const Scene& scene;
  double horizon;
  const ClassifyOptions& classify;
  int probes = 0;
  std::optional<FailureMode> failure;
  bool only_frozen = false;  // the last probe failed by frozen coordinates alone

  bool stable(double h) {
    const Scene s = scene_for_step(scene, h, horizon);
    std::unique_ptr<Engine> engine = make();
    RunOptions options;
    options.record_every = stability_record_every(s, h);
    const Verdict v =
        classify_engine_run(s, run_scene(*engine, s, h, options), engine->info(), classify);
    ++probes;
    failure.reset();
    only_frozen = !v.stable();
    for (const Failure& f : v.failures) only_frozen = only_frozen && f.mode == FailureMode::frozen;
    if (!v.stable()) failure = v.failures.front().mode;
    return v.stable();
  }
};

// The two ends of a bracket: a stable step and an unstable one (either may be the larger).
struct Bracket {
  double stable, unstable;
};

// Bisects `b` geometrically until the ends differ by less than rel_tol (relative); `failure` gets
// the failure at the final unstable end.
Bracket bisect(Prober& p, Bracket b, double rel_tol, std::optional<FailureMode>& failure) {
  while (std::max(b.stable, b.unstable) / std::min(b.stable, b.unstable) - 1.0 > rel_tol) {
    const double mid = std::sqrt(b.stable * b.unstable);
    if (p.stable(mid)) {
      b.stable = mid;
    } else {
      b.unstable = mid;
      failure = p.failure;
    }
  }
  return b;
}

// From a stable lo: doubles h (the last try is the cap itself) until a probe fails, then bisects.
void climb(Prober& p, double lo, const SearchOptions& o, StepSearch& r) {
  while (lo < r.cap) {
    const double h = std::min(2.0 * lo, r.cap);
    if (p.stable(h)) {
      lo = h;
      continue;
    }
    r.limit = p.failure;
    const Bracket b = bisect(p, {lo, h}, o.rel_tol, r.limit);
    r.max_stable_dt = b.stable;
    r.min_unstable_dt = b.unstable;
    return;
  }
  r.max_stable_dt = lo;  // no failure up to the cap
}

// From an unstable h0 that did not fail by freezing alone: halves h until a probe is stable.
void descend(Prober& p, double h0, const SearchOptions& o, StepSearch& r) {
  // Probes below h0 cost more steps: at most max_probe_growth times those of h0 (and
  // max_probe_steps).
  const double budget = std::min(static_cast<double>(o.max_probe_steps),
                                 o.max_probe_growth * std::ceil(r.horizon / h0));
  double hi = h0;
  r.limit = p.failure;
  for (int i = 0; i < o.max_halvings; ++i) {
    const double h = hi / 2.0;
    if (std::ceil(r.horizon / h) > budget) break;
    if (p.stable(h)) {
      const Bracket b = bisect(p, {h, hi}, o.rel_tol, r.limit);
      r.max_stable_dt = b.stable;
      r.min_unstable_dt = b.unstable;
      return;
    }
    hi = h;
    r.limit = p.failure;
  }
  r.min_unstable_dt = hi;  // unstable at every step tried
}

// From an h0 frozen by precision: doubles h (up to the cap) until a probe is stable, bisects that
// edge (min_stable_dt), then climbs from there to the upper edge.
void rise(Prober& p, double h0, const SearchOptions& o, StepSearch& r) {
  for (double frozen = h0; frozen < r.cap;) {
    const double h = std::min(2.0 * frozen, r.cap);
    if (!p.stable(h)) {
      frozen = h;
      continue;
    }
    std::optional<FailureMode> unused;
    r.min_stable_dt = bisect(p, {h, frozen}, o.rel_tol, unused).stable;
    climb(p, h, o, r);
    return;
  }
  r.limit = FailureMode::frozen;  // frozen at every step tried up to the cap
}

}  // namespace

std::int64_t stability_record_every(std::int64_t steps) {
  return steps / 20000 + 1;
}

std::int64_t stability_record_every(const Scene& scene, double h) {
  // The contact laws are judged step by step (classify_engine_run): keep every step of a scene
  // that holds a slide, a bounce or a stack, up to 200000 steps (a longer run is thinned as any
  // other, and classified without its contact laws).
  const std::int64_t steps = step_count(scene, h);
  const bool contact_laws =
      scene.world.contacts && (!slide_setups(scene).empty() || !bounce_setups(scene).empty() ||
                               !stack_setups(scene).empty());
  return contact_laws && steps <= 200000 ? 1 : stability_record_every(steps);
}

Scene scene_for_step(const Scene& scene, double h, double horizon) {
  Scene s = scene;
  const double n = std::max(1.0, std::ceil(horizon / h - 1e-9));
  s.duration = n * h;
  s.timestep = Timestep{h, exact(h)};
  s.timesteps = {s.timestep};
  return s;
}

StepSearch search_max_stable_dt(const EngineFactory& make, const Scene& scene, double h0,
                                const SearchOptions& o, const ClassifyOptions& classify) {
  StepSearch r;
  r.start = h0;
  r.horizon = std::min(scene.duration, static_cast<double>(o.horizon_steps) * h0);
  r.cap = std::max(h0, std::min(o.max_h, scene.duration / 8.0));
  Prober p{make, scene, r.horizon, classify, 0, std::nullopt, false};
  if (p.stable(h0))
    climb(p, h0, o, r);
  else if (p.only_frozen)
    rise(p, h0, o, r);
  else
    descend(p, h0, o, r);
  r.probes = p.probes;
  return r;
}

}  // namespace dropcheck
