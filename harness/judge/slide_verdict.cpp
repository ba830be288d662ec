#include "harness/judge/slide_verdict.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "harness/core/number_format.hpp"
#include "harness/judge/engine_messages.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/oracles/replayed_contact.hpp"

namespace dropcheck {
namespace {

// "stops at step 62, 2.509472 m", "never moves" or "slides on (2.970552 m by the end)".
std::string stop_text(const SlideObservation& o) {
  if (o.stop_step < 0) return printf_string("slides on (%.7g m by the end)", o.distance);
  if (o.stop_step == 0) return "never moves";
  return printf_string("stops at step %lld, %.7g m", static_cast<long long>(o.stop_step),
                       o.distance);
}

// The distance between the run's path and the law's after step n: along the slip, and in how far
// each is off it (0 for a clamp law; a replay's skin lifts it as the run's does).
double apart(const SlidePath& run, const SlidePath& law, std::size_t n) {
  return std::hypot(run.s[n] - law.s[n], run.off[n] - law.off[n]);
}

// The largest distance between the run's path and the law's over the steps both have (a
// non-finite run is infinitely far). The law's path is as long as the run's.
double path_distance(const SlidePath& run, const SlidePath& law) {
  double worst = 0.0;
  for (std::size_t n = 0; n < std::min(run.s.size(), law.s.size()); ++n) {
    const double d = apart(run, law, n);
    worst = std::isfinite(d) ? std::max(worst, d) : INFINITY;
  }
  return worst;
}

// The first step at which the run is over tolerance::kSlideDistance from the law (-1: none).
std::int64_t first_apart(const SlidePath& run, const SlidePath& law) {
  for (std::size_t n = 0; n < std::min(run.s.size(), law.s.size()); ++n)
    if (!(apart(run, law, n) <= tolerance::kSlideDistance)) return static_cast<std::int64_t>(n);
  return -1;
}

SlideObservation observe(const SlidePath& path) {
  return observe_slide(path, tolerance::kStoppedSpeed, tolerance::kSlideDistance);
}

struct LawFit {
  SlideObservation seen;
  double off = 0.0;
  std::int64_t first_off = -1;
  bool follows = false;
};

// How `run` (seen as `seen`) fits the path of its law.
LawFit fit_path(const SlidePath& run, const SlideObservation& seen, const SlidePath& law) {
  LawFit f{observe(law), path_distance(run, law), first_apart(run, law), false};
  f.follows = f.seen.stop_step == seen.stop_step && f.off <= tolerance::kSlideDistance;
  return f;
}

LawFit fit(const SlidePath& run, const SlideObservation& seen, const SlideSetup& s,
           FrictionModel model, double h, PositionUpdate position, const RelativeCfm& soft,
           bool after_position = false) {
  const auto steps = static_cast<std::int64_t>(run.s.size()) - 1;
  return fit_path(run, seen, slide_path(s, model, h, steps, position, soft, after_position));
}

// The neighbouring members of a departing run's slide law, tried in turn: the first whose path it
// follows names the cause (SlideVerdict::instead).
void name_slide_neighbour(SlideVerdict& v, const SlidePath& path, const SlideSetup& s, double h,
                          PositionUpdate position, const RelativeCfm& soft) {
  const auto take = [&](const LawFit& f, const std::string& member) {
    if (!f.follows || !v.instead.empty()) return;
    v.instead = member;
    v.instead_off = f.off;
  };
  for (FrictionModel other : kFrictionModels)
    if (other != v.model && exact_slide_angle(other, s.angle)) {
      take(fit(path, v.seen, s, other, h, position, soft),
           "the " + std::string(to_string(other)) + "'s clamp law");
      if (!v.instead.empty() && !v.instead_model) v.instead_model = other;
    }
  take(fit(path, v.seen, s, v.model, h, position, soft, true),
       "its law with the friction resolved after the position update (the position moves with "
       "the speed before the friction)");
  if (s.pull != 0.0) {
    SlideSetup whole = s;
    whole.g = std::hypot(s.g, s.pull);
    take(fit(path, v.seen, whole, v.model, h, position, soft),
         printf_string("its law with the grip mu*|g| = %.6g m/s^2: the normal force ignores the "
                       "incline (mu*g*cos(theta) = %.6g m/s^2)",
                       s.mu * whole.g, s.mu * s.g));
  }
  if (position != PositionUpdate::Explicit)
    take(fit(path, v.seen, s, v.model, h, PositionUpdate::Explicit, soft),
         "its law with the position moved by the step-start speed (explicit)");
}

// The clamp law's closed forms of the verdict, for a path of `steps` steps.
void clamp_figures(SlideVerdict& v, const SlideSetup& s, double h, std::size_t samples) {
  v.law = slide_to_stop(s.v0, s.mu, s.g, h, v.model, s.angle, s.pull);
  v.end_continuous = slide_distance_continuous(
      s.v0, s.pull, slide_grip(s.mu, s.g, v.model, s.angle), h * static_cast<double>(samples - 1));
}

// How far the replayed law departs from itself when the launch speed moves by kSensitivityUlps
// machine epsilons (relative) either way (SlideVerdict::self_off, self_first). Unsteered, all
// three.
void law_sensitivity(SlideVerdict& v, const Scene& scene, const SlideSetup& s,
                     const ContactSolver& solver, double h, std::int64_t steps) {
  const SlidePath base = replayed_slide_path(scene, s, solver, h, steps);
  for (const double sign : {-1.0, 1.0}) {
    Scene moved = scene;
    Vec3& v0 = moved.bodies[s.body].velocity;
    if (v0.norm() == 0.0) return;
    v.self_measured = true;
    v0 *= 1.0 + sign * kSensitivityUlps * std::numeric_limits<double>::epsilon();
    const SlidePath other = replayed_slide_path(moved, s, solver, h, steps);
    v.self_off = std::max(v.self_off, path_distance(base, other));
    const std::int64_t first = first_apart(base, other);
    if (first >= 0 && (v.self_first < 0 || first < v.self_first)) v.self_first = first;
  }
}

// Against the replay of the engine's solver; the clamp law and, for an iterative solver, a replay
// at 4 times the velocity iterations beside it.
SlideVerdict judge_replayed(const Trajectory& run, const SlidePath& path, const Scene& scene,
                            const SlideSetup& s, const EngineInfo& info, SlideVerdict v, double h) {
  const ContactSolver& solver = info.contact_solver;
  const auto steps = static_cast<std::int64_t>(path.s.size()) - 1;
  v.solver = solver;
  try {
    const LawFit own =
        fit_path(path, v.seen, replayed_slide_path(scene, s, solver, h, steps, &run));
    v.law_seen = own.seen;
    v.off_law = own.off;
    v.first_off = own.first_off;
    v.follows = own.follows;
    if (!v.follows) law_sensitivity(v, scene, s, solver, h, steps);
    ContactSolver more = solver;
    more.velocity_iterations = v.more_iterations = 4 * solver.velocity_iterations;
    if (more.velocity_iterations > 0)
      v.more_seen = observe(replayed_slide_path(scene, s, more, h, steps));
  } catch (const std::invalid_argument& e) {
    v.exact = false;
    v.not_judged = e.what();
    return v;
  }
  clamp_figures(v, s, h, path.s.size());
  v.clamp_seen = observe(slide_path(s, v.model, h, steps, info.law.position));
  return v;
}

// Against Coulomb's law step by step, each step's normal impulse read from the run's momentum
// (harness/oracles/slide_impulses.hpp), within the bounds the engine declares.
SlideVerdict judge_by_momentum(const Trajectory& run, const SlidePath& path, const SlideSetup& s,
                               const EngineInfo& info, SlideVerdict v, double h) {
  const ContactSolver& solver = info.contact_solver;
  const auto steps = static_cast<std::int64_t>(path.s.size()) - 1;
  v.solver = solver;
  const std::vector<SlideImpulse> impulses = slide_impulses(run.body_states(s.body), s, h);
  v.coulomb = coulomb_certificate(impulses, s.mu, s.g, h, solver.coulomb_median_bound,
                                  machine_epsilon(info.scalar));
  const SlidePath own = coulomb_path(impulses, s, s.mu, h);
  v.law_seen = observe(own);
  for (std::size_t n = 0; n < path.s.size(); ++n)
    v.off_law = std::max(v.off_law, std::abs(path.s[n] - own.s[n]));
  v.first_off = v.coulomb->first_bad;
  v.follows = v.coulomb->holds;
  clamp_figures(v, s, h, path.s.size());
  v.clamp_seen = observe(slide_path(s, v.model, h, steps, info.law.position));
  return v;
}

// "Coulomb's law from its momentum: over its 61 slipping steps the friction against the slip is
// 1.00331 of mu*N (bound 0.01); ...": the certificate of a momentum verdict.
std::string coulomb_text(const CoulombCertificate& c, const ContactSolver& solver) {
  std::string t = printf_string(
      "Coulomb's law from its momentum: its median slipping step's friction against the slip is "
      "%.7g of mu*N (bound %.0e; over all %d, %.5g)",
      c.median_ratio, solver.coulomb_median_bound, c.slipping, c.mean_ratio);
  t += printf_string("; mu*N to %.0e on %d steps", kCoulombRounding, c.exact);
  if (c.worst_short_step > 0)
    t += printf_string(", at most %.2g below (step %lld: its contacts slip apart as it rocks)",
                       c.worst_short, static_cast<long long>(c.worst_short_step));
  if (c.stale > 0)
    t += printf_string(", above on %d (by up to %.2g %% at step %lld%s)", c.stale,
                       100.0 * c.worst_over, static_cast<long long>(c.worst_over_step),
                       solver.keeps_stale_friction
                           ? ": a contact that lost its normal impulse mid-step keeps the friction "
                             "earlier iterations gave it"
                           : "");
  if (c.held > 0 && c.creep_step < 0)
    t += printf_string("; %d held steps, none creeping", c.held);
  else if (c.held > 0)
    t += printf_string("; %d held steps, creeping at up to %.2g m/s (step %lld)", c.held, c.creep,
                       static_cast<long long>(c.creep_step));
  t += printf_string("; its normal impulse %.3g to %.3g of m*g*h", c.min_normal, c.max_normal);
  return t;
}

// Why a momentum verdict departs, at its first bad step.
std::string coulomb_departure(const CoulombCertificate& c, const ContactSolver& solver) {
  if (c.pull_step >= 0 && c.pull_step == c.first_bad)
    return "its contact pulls (a negative normal impulse)";
  if (solver.coulomb_median_bound > 0.0)
    return printf_string(
        "its median slipping step's friction is %.6g of mu*N, beyond the bound of %.0e: another "
        "coefficient or combine rule than the scene's mu",
        c.median_ratio, solver.coulomb_median_bound);
  return printf_string(
      "its friction is %.2g below or %.2g above mu*N on a step, where Coulomb's law holds it to "
      "%.0e",
      c.worst_short, c.worst_over, kCoulombRounding);
}

}  // namespace

// The law's own sensitivity explains a departure of its size (within a factor of 10), not one far
// larger.
bool SlideVerdict::rounding_limited() const {
  return !follows && solver && !coulomb && instead.empty() && self_first >= 0 &&
         10.0 * self_off >= off_law;
}

std::string SlideVerdict::limit_text() const {
  return printf_string(
      "its law amplifies rounding: with its launch speed changed by %.0f machine epsilons it "
      "departs from itself by up to %.2g m, first at step %lld, so a departure of this size (%.2g "
      "m) is rounding it amplifies, not another law",
      kSensitivityUlps, self_off, static_cast<long long>(self_first), off_law);
}

SlideVerdict judge_slide(const Trajectory& run, const SlideSetup& s, FrictionModel model, double h,
                         PositionUpdate position, const RelativeCfm& soft) {
  SlideVerdict v;
  v.model = model;
  v.soft = soft;
  const SlidePath path = observed_slide_path(run, s);
  v.seen = observe_slide(path, tolerance::kStoppedSpeed, tolerance::kSlideDistance);
  v.exact = exact_slide_angle(model, s.angle);
  if (!v.exact) {
    v.not_judged =
        "the " + std::string(to_string(model)) + "'s slide is exact at 0 and 45 degrees only";
    return v;
  }
  if (!run.keeps_every_step()) {
    v.exact = false;
    v.not_judged = "the run did not keep every step";
    return v;
  }
  clamp_figures(v, s, h, path.s.size());
  const LawFit own = fit(path, v.seen, s, model, h, position, soft);
  v.law_seen = own.seen;
  v.off_law = own.off;
  v.first_off = own.first_off;
  v.follows = own.follows;
  if (v.follows) return v;
  const SlidePath ahead = slide_steps(s, model, h, path, position, soft);
  v.off_steps = path_distance(path, ahead);
  for (std::size_t n = 0; n < path.v.size(); ++n)
    v.off_steps_speed = std::max(v.off_steps_speed, std::abs(path.v[n] - ahead.v[n]));
  v.follows =
      v.off_steps <= tolerance::kSlideDistance && v.off_steps_speed <= tolerance::kStepSpeed;
  if (v.follows) return v;
  name_slide_neighbour(v, path, s, h, position, soft);
  return v;
}

SlideVerdict judge_slide(const Trajectory& run, const Scene& scene, const SlideSetup& s,
                         const EngineInfo& info, double h) {
  if (held_by_momentum(info.contact_solver)) {
    SlideVerdict v;
    v.model = info.friction_model;
    const SlidePath path = observed_slide_path(run, s);
    v.seen = observe(path);
    v.exact = run.keeps_every_step();
    if (!v.exact) {
      v.not_judged = "the run did not keep every step";
      return v;
    }
    return judge_by_momentum(run, path, s, info, v, h);
  }
  if (!replayed(info.contact_solver)) {
    SlideVerdict v =
        judge_slide(run, s, info.friction_model, h, info.law.position, info.relative_cfm);
    if (!v.follows && v.instead.empty()) v.engine_said = engine_said(run, info);
    return v;
  }
  SlideVerdict v;
  v.model = info.friction_model;
  const SlidePath path = observed_slide_path(run, s);
  v.seen = observe(path);
  v.exact = exact_slide_angle(v.model, s.angle) && run.keeps_every_step();
  if (!v.exact) {
    v.not_judged = run.keeps_every_step()
                       ? "the replay's clamp law is exact at 0 and 45 degrees only"
                       : "the run did not keep every step";
    return v;
  }
  return judge_replayed(run, path, scene, s, info, v, h);
}

std::string SlideVerdict::sentence() const {
  std::string text = stop_text(seen);
  if (!exact) return text + "; not judged: " + not_judged;
  const std::string clamp = std::string(to_string(model)) + "'s clamp law" +
                            (soft.cfm > 0.0 ? " under " + describe(soft) : std::string()) + ": ";
  const std::string continuous =
      law.stops && law.stop_step > 0
          ? printf_string(" (continuous: %.5g s, %.5g m)", law.stop_time, law.distance)
          : printf_string(" (continuous: %.7g m by the end)", end_continuous);
  if (coulomb)
    text += "; its " + describe(*solver) + ": " + coulomb_text(*coulomb, *solver) +
            "; that law with its normal impulses: " + stop_text(law_seen);
  else if (solver)
    text += "; its " + describe(*solver) + ": " + stop_text(law_seen);
  else
    text += "; its " + clamp + stop_text(law_seen) + continuous;
  text += printf_string(", %.2g m off it", off_law);
  // What leaves a path that follows its law step by step: a float engine's rounding, or the tilt
  // that a relative CFM lets the friction give the box (DART: about 1e-6 rad/s, which sets it
  // rocking back once it stops), which its law leaves out.
  const char* drift = soft.cfm > 0.0 ? "the box tilts under its regularised rows, which the law "
                                       "leaves out"
                                     : "the run's rounding";
  if (off_steps >= 0.0)
    text += follows ? printf_string(
                          ", every step as its law to %.2g m and %.2g m/s (the drift: "
                          "%s)",
                          off_steps, off_steps_speed, drift)
                    : printf_string(" (one step from its own state: %.2g m, %.2g m/s)", off_steps,
                                    off_steps_speed);
  if (solver) {
    // What the solver leaves: the clamp law, and the replay with more iterations.
    text += "; the " + clamp + stop_text(clamp_seen) + continuous;
    if (more_iterations > 0 && !coulomb)
      text += printf_string(
                  ", %s at %d velocity iterations: ",
                  more_seen.stop_step == clamp_seen.stop_step ? "as the replay" : "the replay",
                  more_iterations) +
              stop_text(more_seen);
  }
  if (follows) return text;
  text += " DEPARTS";
  if (coulomb)
    return text + printf_string(" at step %lld: ", static_cast<long long>(first_off)) +
           coulomb_departure(*coulomb, *solver);
  if (first_off >= 0)
    text += printf_string(" at step %lld (first over %.2g m)", static_cast<long long>(first_off),
                          tolerance::kSlideDistance);
  if (!instead.empty())
    return text + ": it follows " + instead + printf_string(" instead (to %.2g m)", instead_off);
  if (rounding_limited()) return text + ": " + limit_text();
  if (solver)
    return text + ": no cause named (" +
           (!self_measured ? std::string("its law's sensitivity is measured on a launched slide")
            : self_first >= 0
                ? printf_string("its law departs from itself by only %.2g m", self_off)
                : std::string("its law holds to its own launch speed's rounding")) +
           "); `dropcheck identify SCENE --engine E` tries every solver dropcheck replays";
  if (!engine_said.empty())
    return text + ": no neighbouring member of its law fits; " + engine_said;
  return text +
         ": UNEXPLAINED, no neighbouring member fits (another friction model, the friction after "
         "the position update, the grip of the whole gravity, an explicit position update); "
         "`dropcheck identify SCENE --engine E` names the friction model and position update "
         "its run fits best";
}

}  // namespace dropcheck
