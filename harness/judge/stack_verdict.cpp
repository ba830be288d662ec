#include "harness/judge/stack_verdict.hpp"

#include <algorithm>
#include <cmath>

#include "harness/core/number_format.hpp"
#include "harness/judge/tolerances.hpp"

namespace dropcheck {

std::vector<StackBodyVerdict> judge_stack(const Trajectory& run, const StackSetup& setup,
                                          const EngineInfo& info, double h) {
  std::vector<StackBodyVerdict> out;
  if (run.samples() == 0) return out;
  const StillCriteria window;
  const std::int64_t from = run.recorded.back() - std::llround(window.seconds / h);
  // The column's last landing, for a body dropped onto it from rest (the continuous fall under the
  // run's drag, harness/oracles/landing.hpp). Stillness is judged only over a window wholly after.
  double landing = 0.0;
  for (const StackLevel& l : setup.levels) {
    const double y0 = run.at(0, l.body).position.y();
    if (y0 > l.rest_height)
      landing = std::max(
          landing, contact_time_continuous(y0, 0.0, -setup.g, setup.damping_rate, l.rest_height));
  }
  const bool still_judged = static_cast<double>(from) * h > landing;  // false for NaN
  const std::vector<StackPrediction> predicted =
      predict_stack(setup, info, h, run.recorded.back(), from);
  for (std::size_t k = 0; k < setup.levels.size(); ++k) {
    const StackLevel& l = setup.levels[k];
    StackBodyVerdict v;
    v.body = l.body;
    v.level = l.level;
    v.predicted = predicted[k];
    const Vec3 start = run.at(0, l.body).position;
    for (std::size_t s = 0; s < run.samples(); ++s) {
      const Vec3& p = run.at(s, l.body).position;
      const double d = std::hypot(p.x() - start.x(), p.z() - start.z());
      v.drift = std::isfinite(d) ? std::max(v.drift, d) : INFINITY;
    }
    const BodyState& last = run.final_state(l.body);
    v.sink = l.rest_height + v.predicted.offset - last.position.y();
    v.still = still_figures(run, l.body, from);
    const double floor_bound = info.stack_law.sink_bound;
    // An exact law is held to its bound; a steady-state one to a band around its sink.
    v.sink_ok = v.predicted.exact
                    ? std::abs(v.sink - v.predicted.sink) <= floor_bound
                    : v.sink >= tolerance::kStackSinkLow * v.predicted.sink - floor_bound &&
                          v.sink <= tolerance::kStackSink * v.predicted.sink + floor_bound;
    // Not through the floor: its centre ends above the floor's top (its bottom no deeper in the
    // floor than its half height).
    v.above_floor = std::isfinite(last.position.y()) && last.position.y() >= setup.floor_top;
    v.drift_ok = v.drift <= info.stack_law.drift_bound;
    v.still_judged = still_judged;
    // An exact law's own settling motion is allowed on top of the bound.
    const StillFigures& law_still = v.predicted.still;
    v.still_ok = !still_judged || (v.still.speed <= law_still.speed + info.stack_law.still_bound &&
                                   v.still.range <= law_still.range + info.stack_law.still_bound);
    if (!v.sink_ok) {
      // Out of its band: the first step of its last stretch away from its law's rest height.
      // The band's edge it crossed, as a distance from its law's sink.
      const double expected_y = l.rest_height + v.predicted.offset - v.predicted.sink;
      const double band = v.predicted.exact ? floor_bound
                          : v.sink > v.predicted.sink
                              ? (tolerance::kStackSink - 1.0) * v.predicted.sink + floor_bound
                              : (1.0 - tolerance::kStackSinkLow) * v.predicted.sink + floor_bound;
      // Under a contact resolved after the position update each level falls one step's fall onto
      // the one below: level n rests n of them low.
      v.departure = rest_departure(
          run, l.body, expected_y, band, l.load * setup.g,
          one_step_fall(info.law, std::exp(-setup.damping_rate * h), h, setup.g), l.level);
    }
    if (!v.drift_ok)
      v.departure = earlier(v.departure, drift_departure(run, l.body, info.stack_law.drift_bound));
    if (!v.still_ok)
      v.departure =
          earlier(v.departure, stillness_departure(run, l.body, from,
                                                   law_still.speed + info.stack_law.still_bound,
                                                   law_still.range + info.stack_law.still_bound));
    out.push_back(v);
  }
  // A contact the sweeps cannot hold lets the load squeeze every body of the column, those under
  // it too: the limit is the stack's.
  const auto worst = std::max_element(out.begin(), out.end(),
                                      [](const StackBodyVerdict& a, const StackBodyVerdict& b) {
                                        return a.predicted.residual < b.predicted.residual;
                                      });
  if (worst != out.end() && worst->predicted.residual > kUnheldResidual)
    for (StackBodyVerdict& v : out) {
      v.unheld = true;
      v.limiting = worst->predicted;
    }
  // An exact law that sinks a box past its face contact no longer describes the column: a named
  // limit, the floor waived where the law itself ends a body below it.
  if (!out.empty() && out.front().predicted.past_faces >= 0)
    for (std::size_t k = 0; k < out.size(); ++k) {
      StackBodyVerdict& v = out[k];
      v.unheld = true;
      v.limiting = v.predicted;
      v.above_floor =
          v.above_floor || setup.levels[k].rest_height - v.predicted.sink < setup.floor_top;
    }
  return out;
}

std::string StackBodyVerdict::sentence() const {
  std::string text =
      printf_string("(level %d) sinks %.4g m (its law: %.4g m", level, sink, predicted.sink);
  text += predicted.offset != 0.0 ? printf_string(", rest offset %.4g m)", predicted.offset)
                                  : std::string(")");
  if (!sink_ok) text += " OUT OF BOUNDS";
  text += printf_string(", drift %.2g m", drift) + (drift_ok ? "" : " TOO FAR");
  text += still_judged ? printf_string(", still: %.2g m/s, %.2g m", still.speed, still.range) +
                             (still_ok ? "" : " NOT STILL")
                       : std::string(
                             ", stillness not judged: the run ends less than 2 s after "
                             "the column's last landing");
  if (!passes() && departure.step >= 0) text += "; " + departure.sentence();
  return text;
}

std::string StackBodyVerdict::limit_text() const {
  if (limiting.past_faces >= 0)
    return printf_string(
        "beyond its law: by step %lld the law sinks a box's centre below the top of the one "
        "under it (%.4g m down here by the end: a load its capped push-out cannot carry, or a "
        "landing that deep), past the face contacts the law steps",
        static_cast<long long>(limiting.past_faces), limiting.sink);
  return printf_string(
      "not held, as its solver's sweeps predict: each sweep leaves %.4g of the error between "
      "%.4g kg and the %.4g kg on it, %.2g after a step's sweeps",
      limiting.load / (limiting.load + limiting.mass), limiting.mass, limiting.load,
      limiting.residual);
}

}  // namespace dropcheck
