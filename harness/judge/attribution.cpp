#include "harness/judge/attribution.hpp"

#include <algorithm>
#include <cmath>

#include "harness/core/number_format.hpp"
#include "harness/oracles/own_rotation.hpp"

namespace dropcheck {
namespace {

// "damping order", "position update", "damping order + position update" from law_difference's key;
// "laws" when the members are one (a difference below rounding never reaches the sentence).
std::string law_difference_words(std::string key) {
  if (key.empty()) return "laws";
  for (char& c : key)
    if (c == '-') c = ' ';
  return key;
}

bool departs_in_rotation(const OwnLawVerdict& v) {
  // Judged only with a meaningful tolerance, like the linear residual (a law that blows up has none
  // and blames nobody here; its own-law verdict says so).
  return v.rotation && v.rotation_judged() &&
         (v.residual_angle > v.tolerance_angle || v.residual_w > v.tolerance_w);
}

bool departs(const OwnLawVerdict& v) {
  return v.residual_x > v.tolerance.x || v.residual_v > v.tolerance.v || departs_in_rotation(v);
}

std::int64_t first_clamp(std::int64_t a, std::int64_t b) {
  if (a < 0) return b;
  if (b < 0) return a;
  return std::min(a, b);
}

// "ours departs from its own law (v = ...) by 32.7 cm (tolerance 1.2e-6 m)", or from its
// rotational law by an angle.
std::string departure(const OwnLawVerdict& v) {
  if (departs_in_rotation(v) && v.residual_x <= v.tolerance.x && v.residual_v <= v.tolerance.v)
    return v.engine + " departs from its own rotational law (" + v.rotation_law + ") by " +
           g3(v.residual_angle) + " rad, |w - law| " + g3(v.residual_w) + " rad/s (tolerance " +
           g3(v.tolerance_angle) + " rad, " + g3(v.tolerance_w) + " rad/s)";
  return v.engine + " departs from its own law (" + v.law + ") by " + format_length(v.residual_x) +
         " (tolerance " + format_length(v.tolerance.x) + ")";
}

std::string follows(const OwnLawVerdict& v) {
  return v.engine + " follows its own law to " + format_length(v.residual_x);
}

// What one engine's run may add to the distance between two runs beyond the laws' difference: its
// own-law tolerance (rounding, up to that bound anywhere). An error-controlled engine's tolerance
// is its accuracy budget, which may exceed its actual error by orders of magnitude (own_law.cpp),
// so its measured departure from its law is used: |run - law| bounds its share exactly.
double share_of_budget(const EngineInfo& info, const OwnLawVerdict& v) {
  return info.law.scheme == Scheme::ErrorControlled ? v.residual_x : v.tolerance.x;
}

}  // namespace

bool Attribution::explained() const {
  return !departs(engine_law) && !departs(reference_law);
}

std::string Attribution::blamed() const {
  std::string out;
  for (const OwnLawVerdict* v : {&engine_law, &reference_law})
    if (departs(*v)) out += (out.empty() ? "" : ", ") + v->engine;
  return out;
}

Attribution attribute(const RunWithLaws& e, const RunWithLaws& r, bool damped) {
  Attribution a;
  a.engine = e.run.engine;
  a.reference = r.run.engine;
  a.law_difference = dropcheck::law_difference(e.info.law, r.info.law, damped);
  a.clamped_from = first_clamp(e.run.first_clamped_step, r.run.first_clamped_step);
  Trajectory er = e.run, rr = r.run;
  er.first_clamped_step = rr.first_clamped_step = a.clamped_from;  // both stop at either clamp
  a.engine_law = judge_own_law(e.info, er, e.own, e.exact);
  a.reference_law = judge_own_law(r.info, rr, r.own, r.exact);
  a.budget = share_of_budget(e.info, a.engine_law) + share_of_budget(r.info, a.reference_law);
  const std::size_t samples = std::min({e.run.samples(), r.run.samples(), e.own.samples(),
                                        r.own.samples(), e.exact.samples(), r.exact.samples()});
  for (std::size_t s = 0; s < samples; ++s) {
    if (a.clamped_from >= 0 && e.run.recorded[s] >= a.clamped_from) break;
    double final_dx = 0.0;
    for (std::size_t b = 0; b < e.run.bodies(); ++b) {
      const Vec3 diff = e.run.at(s, b).position - r.run.at(s, b).position;
      const Vec3 law = e.exact.at(s, b).position - r.exact.at(s, b).position;
      const Vec3 own = e.own.at(s, b).position - r.own.at(s, b).position;
      a.total = std::max(a.total, diff.norm());
      a.law_part = std::max(a.law_part, law.norm());
      a.precision_part = std::max(a.precision_part, (own - law).norm());
      a.residual = std::max(a.residual, (diff - own).norm());
      final_dx = std::max(final_dx, diff.norm());
    }
    a.final_total = final_dx;
    a.final_t = e.run.time(s);
  }
  if (e.run.rotates && r.run.rotates && e.own.rotates && r.own.rotates) {
    std::size_t compared = 0;
    while (compared < samples && (a.clamped_from < 0 || e.run.recorded[compared] < a.clamped_from))
      ++compared;
    a.rotation = true;
    a.rotation_total = rotation_residual(e.run, r.run.rotations, compared).angle;
    a.rotation_law_part = rotation_residual(e.own, r.own.rotations, compared).angle;
    a.rotation_laws =
        rotation_law_key(e.info.rotation_law) + " vs " + rotation_law_key(r.info.rotation_law);
    // One member with the damping in one place: the laws are one law, and what separates the two
    // predictions is each engine's rounding: its scalar (a float run amplified through a tumble)
    // and its own operation order (DART's rotation-vector round trip).
    a.same_rotation_law = e.info.rotation_law == r.info.rotation_law &&
                          law_difference(e.info.law, r.info.law).empty();
  }
  return a;
}

bool Attribution::rotation_laws_differ() const {
  return rotation && !same_rotation_law &&
         rotation_law_part > engine_law.tolerance_angle + reference_law.tolerance_angle;
}

std::string Attribution::sentence() const {
  std::string why;
  const std::string precision = "precision part " + format_length(precision_part);
  if (total == 0.0 && explained()) {
    why = "identical";
  } else if (!explained()) {
    // Blame only the engine(s) beyond their own tolerance; say that the other follows its law.
    std::string who;
    for (const OwnLawVerdict* v : {&engine_law, &reference_law})
      who += (who.empty() ? "" : "; ") + (departs(*v) ? departure(*v) : follows(*v));
    why = printf_string("UNEXPLAINED residual %s: %s; the laws explain %s, %s",
                        format_length(residual), who, format_length(law_part), precision);
  } else if (law_part <= budget) {
    // Same discrete law (or laws that differ by less than rounding): nothing for the laws to split.
    why = printf_string(
        "the two discrete laws agree, so all of it is rounding (%s; residual %s, budget %s)",
        precision, format_length(residual), format_length(budget));
  } else {
    const double share = law_part >= total ? 100.0 : 100.0 * law_part / total;
    why =
        printf_string("%s from the two discrete laws (%s); %s; residual %s, within rounding",
                      share >= 99.95 ? "all of it" : std::to_string(static_cast<int>(share)) + "%",
                      law_difference_words(law_difference), precision, format_length(residual));
  }
  std::string out = printf_string("%s vs %s: %s at t = %g s (max %s), %s", engine, reference,
                                  format_length(final_total), final_t, format_length(total), why);
  if (rotation && explained()) {
    if (rotation_laws_differ())
      out += printf_string(
          "; rotation: up to %s rad apart, the two rotational laws (%s) %s rad apart, each "
          "engine within its tolerance of its own",
          g3(rotation_total), rotation_laws, g3(rotation_law_part));
    else if (same_rotation_law)
      out += printf_string(
          "; rotation: up to %s rad apart under one rotational law (%s): each engine's rounding, "
          "amplified by the motion",
          g3(rotation_total), rotation_laws);
    else
      out += printf_string(
          "; rotation: up to %s rad apart, the two rotational laws (%s) agree to rounding",
          g3(rotation_total), rotation_laws);
  }
  if (clamped_from >= 0)
    out += "; a speed clamp reported by the engine at step " + std::to_string(clamped_from) +
           " ends the comparison there (clamp, not a departure)";
  return out + ".";
}

}  // namespace dropcheck
