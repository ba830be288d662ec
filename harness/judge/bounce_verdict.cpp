#include "harness/judge/bounce_verdict.hpp"

#include <cmath>
#include <optional>
#include <stdexcept>

#include "harness/core/number_format.hpp"
#include "harness/judge/engine_messages.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/oracles/replayed_contact.hpp"

namespace dropcheck {
namespace {

struct PathGap {
  double worst = 0.0;
  std::int64_t step = 0;
  std::int64_t first = -1;  // the first step over tolerance::kBouncePath; -1 none
};

// The largest |gap| difference between a run's path and a law's, over the steps both have, and
// the first step where it exceeds the path tolerance.
PathGap path_gap(const BouncePath& run, const BouncePath& law) {
  PathGap p;
  const std::size_t n = std::min(run.gap.size(), law.gap.size());
  for (std::size_t i = 0; i < n; ++i) {
    const double d = std::abs(run.gap[i] - law.gap[i]);
    const auto step = static_cast<std::int64_t>(i);
    if (p.first < 0 && !(d <= tolerance::kBouncePath)) p.first = step;
    if (std::isnan(d)) return {d, step, p.first};  // never "within" anything
    if (d > p.worst) p = {d, step, p.first};
  }
  return p;
}

// The members of `law` that move its path off the ideal one by more than the path tolerance, each
// tried alone.
std::vector<std::string> departing_members(const BounceLaw& law, const BounceSetup& s, double h,
                                           const BouncePath& ideal) {
  std::vector<std::string> out;
  const auto steps = static_cast<std::int64_t>(ideal.gap.size()) - 1;
  const auto moves = [&](const BounceLaw& alone) {
    return path_gap(bounce_path(alone, s.h0, s.e, s.g, h, steps, s.size), ideal).worst >
           tolerance::kBouncePath;
  };
  if (law.erp > 0.0 &&
      moves({.erp = law.erp, .max_push = law.max_push, .push_in_position = law.push_in_position}))
    out.push_back(push_text(law));
  if ((law.threshold > 0.0 || law.free_approach || std::isfinite(law.max_rebound)) &&
      moves({.threshold = law.threshold,
             .free_approach = law.free_approach,
             .threshold_on_rebound = law.threshold_on_rebound,
             .max_rebound = law.max_rebound}))
    out.push_back(restitution_text(law));
  if ((law.contact_distance > 0.0 || law.contact_distance_per_size > 0.0) &&
      moves({.contact_distance = law.contact_distance,
             .contact_distance_per_size = law.contact_distance_per_size}))
    out.push_back(contact_distance_text(law) +
                  printf_string(" (%.4g m here)",
                                law.contact_distance + law.contact_distance_per_size * s.size));
  if (law.cfm > 0.0 && moves({.cfm = law.cfm})) out.push_back(cfm_text(law));
  return out;
}

}  // namespace

std::string apex_text(const std::vector<double>& apexes) {
  if (apexes.empty()) return "none";
  std::string text;
  for (double a : apexes) text += (text.empty() ? "" : ", ") + printf_string("%.4g", a);
  return text + " m";
}

namespace {

// Every law's path is step by step: a run that skipped steps cannot be laid beside it.
constexpr const char* kSkippedSteps = "the run did not keep every step";

// A verdict that judges nothing, saying why (`follows` so that it raises no failure).
BounceVerdict unjudged(const std::string& why, std::optional<ContactSolver> solver) {
  BounceVerdict v;
  v.solver = solver;
  v.not_judged = why;
  v.follows = true;
  return v;
}

// The verdict of the run's path `seen` against its law's path `predicted`.
BounceVerdict judge_paths(const BouncePath& seen, const BouncePath& predicted, const BounceSetup& s,
                          const BounceLaw& law, double h) {
  BounceVerdict v;
  v.law = law;
  const auto steps = static_cast<std::int64_t>(seen.gap.size()) - 1;
  const BouncePath ideal = bounce_path(kIdealBounce, s.h0, s.e, s.g, h, steps);
  v.seen = observe_bounce(seen.gap, seen.v, s.g, h);
  v.predicted = observe_bounce(predicted.gap, predicted.v, s.g, h);
  v.ideal = observe_bounce(ideal.gap, ideal.v, s.g, h);
  v.closed = bounce(s.h0, s.e, s.g, h);
  const PathGap to_law = path_gap(seen, predicted);
  v.worst_gap = to_law.worst;
  v.worst_step = to_law.step;
  v.first_step = to_law.first;
  v.follows = to_law.worst <= tolerance::kBouncePath;
  v.follows_ideal = path_gap(seen, ideal).worst <= tolerance::kBouncePath;
  v.law_to_ideal = path_gap(predicted, ideal).worst;
  double before = s.h0;
  for (double a : v.seen.apexes) {
    v.energy_rises = v.energy_rises || a > before + tolerance::kBouncePath;
    before = a;
  }
  return v;
}

// The neighbouring members of a departing run's bounce law, tried in turn: the first whose path
// the run follows names the cause (BounceVerdict::instead).
void name_bounce_neighbour(BounceVerdict& v, const BouncePath& seen, const BounceSetup& s,
                           const BounceLaw& law, double h) {
  const auto steps = static_cast<std::int64_t>(seen.gap.size()) - 1;
  const auto take = [&](const BounceLaw& member, double e, const std::string& text) {
    if (!v.instead.empty()) return;
    const PathGap g = path_gap(seen, bounce_path(member, s.h0, e, s.g, h, steps, s.size));
    if (!(g.worst <= tolerance::kBouncePath)) return;  // NaN: no member fits
    v.instead = text;
    v.instead_off = g.worst;
  };
  take(kIdealBounce, s.e, "the ideal law (" + describe(kIdealBounce) + ")");
  take(law, 2.0 * s.e,
       printf_string("its law with the restitution applied twice (a rebound of 2e = %.4g of the "
                     "approach)",
                     2.0 * s.e));
  BounceLaw other = law;
  other.free_approach = !law.free_approach;
  take(other, s.e,
       law.free_approach ? "its law with the restitution of the step-start approach"
                         : "its law with the restitution of the approach after the step's gravity "
                           "(applied one step late)");
  BounceLaw late = law;
  late.resolved_after_position = true;
  take(late, s.e,
       "its law with the contact resolved after the position update (the position moves with the "
       "speed before the contact)");
  take({.erp = 1.0, .push_in_position = true, .touching = true}, s.e,
       "the law that snaps the body to the surface at contact (" +
           describe(BounceLaw{.erp = 1.0, .push_in_position = true, .touching = true}) + ")");
}

}  // namespace

BounceVerdict judge_bounce(const Trajectory& run, const BounceSetup& s, const BounceLaw& law,
                           double h) {
  if (!run.keeps_every_step()) return unjudged(kSkippedSteps, std::nullopt);
  const BouncePath seen = observed_path(run, s);
  const auto steps = static_cast<std::int64_t>(seen.gap.size()) - 1;
  const BouncePath predicted = bounce_path(law, s.h0, s.e, s.g, h, steps, s.size);
  BounceVerdict v = judge_paths(seen, predicted, s, law, h);
  if (!v.follows) {
    const BouncePath ahead = bounce_steps(law, seen, s.e, s.g, h, s.size);
    const PathGap local = path_gap(seen, ahead);
    v.step_gap = local.worst;
    v.step_worst = local.step;
    for (std::size_t n = 0; n < seen.v.size(); ++n)
      v.step_speed = std::max(v.step_speed, std::abs(seen.v[n] - ahead.v[n]));
    v.follows = local.worst <= tolerance::kBouncePath && v.step_speed <= tolerance::kStepSpeed;
    const std::size_t n = std::min(seen.gap.size(), predicted.gap.size());
    for (std::size_t i = 0; i < n && v.decided_step < 0; ++i)
      if (bounce_contact(law, seen.gap[i], s.size) !=
          bounce_contact(law, predicted.gap[i], s.size)) {
        v.decided_step = static_cast<std::int64_t>(i);
        v.run_gap_there = seen.gap[i];
        v.law_gap_there = predicted.gap[i];
      }
  }
  if (v.law_to_ideal > tolerance::kBouncePath) {
    v.causes = departing_members(law, s, h, bounce_path(kIdealBounce, s.h0, s.e, s.g, h, steps));
    if (v.causes.empty()) v.causes.push_back("its members together (none alone)");
  }
  if (!v.follows) name_bounce_neighbour(v, seen, s, law, h);
  return v;
}

BounceVerdict judge_bounce(const Trajectory& run, const Scene& scene, const BounceSetup& s,
                           const EngineInfo& info, double h) {
  if (!replayed(info.contact_solver)) {
    BounceVerdict v = judge_bounce(run, s, info.bounce_law, h);
    if (!v.follows && v.instead.empty()) v.engine_said = engine_said(run, info);
    return v;
  }
  const auto not_judged = [&](const std::string& why) {
    return unjudged(why, info.contact_solver);
  };
  if (!run.keeps_every_step()) return not_judged(kSkippedSteps);
  const BouncePath seen = observed_path(run, s);
  const auto steps = static_cast<std::int64_t>(seen.gap.size()) - 1;
  BouncePath predicted;
  try {
    predicted = replayed_bounce_path(scene, s, info.contact_solver, h, steps);
  } catch (const std::invalid_argument& e) {
    return not_judged(e.what());
  }
  BounceVerdict v = judge_paths(seen, predicted, s, info.bounce_law, h);
  v.solver = info.contact_solver;
  // The replay is the engine's whole step: what moves it off the ideal law is its solver.
  if (v.law_to_ideal > tolerance::kBouncePath)
    v.causes.push_back("its solver's own step: " + describe(info.contact_solver));
  return v;
}

// Why a run that follows its law at every step parts from the law's path: where a contact is
// decided on the other side (computed in judge_bounce), or the rounding alone.
std::string BounceVerdict::parting_text() const {
  const auto side = [](double gap) {
    return gap < 0.0   ? printf_string("%.2g m into the floor", -gap)
           : gap > 0.0 ? printf_string("%.2g m above it", gap)
                       : std::string("touching it");
  };
  if (decided_step < 0) return "the run's rounding, amplified over the flight";
  return printf_string("step %lld starts ", static_cast<long long>(decided_step + 1)) +
         side(law_gap_there) + " in the law and " + side(run_gap_there) +
         " in the run, so the two decide its contact on either side";
}

std::string BounceVerdict::sentence() const {
  if (!not_judged.empty()) return "not judged: " + not_judged;
  std::string text =
      seen.contact_step < 0
          ? std::string("never reaches the floor")
          : printf_string("hits at step %lld at %.4g m/s, leaves at %.4g m/s, apexes ",
                          static_cast<long long>(seen.contact_step), seen.speed_in,
                          seen.speed_out) +
                apex_text(seen.apexes);
  if (energy_rises) text += " (ENERGY RISES)";
  text += "; its law (" + (solver ? describe(*solver) : describe(law)) + "): ";
  if (follows && step_gap < 0.0)
    text += printf_string("the same path to %.2g m", worst_gap);
  else if (follows)
    text += printf_string(
                "every step as its law to %.2g m and %.2g m/s; the paths part at step %lld by "
                "%.3g m: ",
                step_gap, step_speed, static_cast<long long>(first_step), worst_gap) +
            parting_text();
  else
    // A replay is not stepped from the run's own state (its solver carries impulses between
    // steps): no one-step figure then.
    text +=
        printf_string(
            "DEPARTS at step %lld (first over %.2g m; the largest gap %.3g m at step "
            "%lld",
            static_cast<long long>(first_step), tolerance::kBouncePath, worst_gap,
            static_cast<long long>(worst_step)) +
        (step_gap < 0.0 ? std::string(")")
                        : printf_string("; one step from its own state: %.3g m at step %lld, "
                                        "%.3g m/s)",
                                        step_gap, static_cast<long long>(step_worst), step_speed));
  if (!follows && !instead.empty())
    text += ": it follows " + instead + printf_string(" instead (to %.2g m)", instead_off);
  else if (!follows && !engine_said.empty())
    text += ": no neighbouring member of its law fits; " + engine_said;
  else if (!follows && !solver)
    text +=
        ": UNEXPLAINED, no neighbouring member fits (the ideal law, the restitution applied twice, "
        "the approach read on the other side of the step's gravity, the contact resolved after the "
        "position update, the body snapped to the surface); `dropcheck identify SCENE --engine E` "
        "lays its run beside every declared bounce law";
  if (law_to_ideal > tolerance::kBouncePath) {
    text += printf_string("; its law is %.3g m off the ideal law (apexes ", law_to_ideal) +
            apex_text(ideal.apexes) + ")";
    for (std::size_t i = 0; i < causes.size(); ++i) text += (i ? " and " : ": ") + causes[i];
  }
  text += "; continuous apexes " + apex_text(closed.apexes);
  return text;
}

}  // namespace dropcheck
