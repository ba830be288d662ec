#include "harness/judge/resting_departure.hpp"

#include <algorithm>
#include <cmath>

#include "harness/core/number_format.hpp"

namespace dropcheck {

std::string RestingDeparture::sentence() const {
  if (step < 0) return {};
  return printf_string("first departs at step %lld (%s): ", static_cast<long long>(step),
                       quantity.c_str()) +
         cause;
}

RestingDeparture earlier(const RestingDeparture& a, const RestingDeparture& b) {
  if (a.step < 0) return b;
  if (b.step < 0) return a;
  return b.step < a.step ? b : a;
}

RestingDeparture rebound_departure(const Trajectory& run, std::size_t body, std::int64_t contact,
                                   double rest_y, double limit) {
  RestingDeparture d;
  if (contact < 0) return d;
  double meets = 0.0, leaves = 0.0;  // m/s: the fastest approach and departure from contact on
  for (std::size_t n = 0; n < run.samples(); ++n) {
    if (run.recorded[n] + 1 < contact) continue;
    const BodyState& s = run.at(n, body);
    meets = std::min(meets, s.velocity.y());
    if (run.recorded[n] < contact) continue;
    leaves = std::max(leaves, s.velocity.y());
    if (s.position.y() - rest_y > limit) {
      d.step = run.recorded[n];
      d.quantity = "rebound";
      d.cause = printf_string(
          "%.3g m above its rest, having left the floor at %.3g m/s after meeting it at %.3g "
          "m/s: a restitution of %.2g, where its law comes to rest",
          s.position.y() - rest_y, leaves, -meets, meets < 0.0 ? leaves / -meets : 0.0);
      return d;
    }
  }
  return d;
}

RestingDeparture rest_departure(const Trajectory& run, std::size_t body, double expected_y,
                                double tolerance, double weight, double one_step_fall, int level) {
  RestingDeparture d;
  if (run.samples() == 0) return d;
  const double off = run.final_state(body).position.y() - expected_y;
  if (std::abs(off) <= tolerance) return d;  // NaN departs
  // Beyond the tolerance on the side it ends on (a stack starting at its geometry is not yet
  // below the sink its law reaches).
  const auto beyond = [&](std::size_t n) {
    const double o = run.at(n, body).position.y() - expected_y;
    if (!std::isfinite(o) || !std::isfinite(off)) return !(std::abs(o) <= tolerance);
    return std::abs(o) > tolerance && (o < 0.0) == (off < 0.0);
  };
  std::size_t first = run.samples() - 1;
  while (first > 0 && beyond(first - 1)) --first;
  d.step = run.recorded[first];
  d.quantity = "rest height";
  const double fell = level * one_step_fall;  // each level falls onto the one below it
  const bool fell_first = fell > 0.0 && std::abs(-off - fell) <= 1e-3 * fell;
  d.cause = !std::isfinite(off) ? std::string("its height is no longer finite")
            : fell_first
                ? printf_string(
                      "it rests %.4g m below, and stays: %d x one step's fall from rest under its "
                      "law (%.4g m), one for each contact under it, so its contact is resolved "
                      "after the position update (each step moves it with the speed before the "
                      "contact, and the push-out returns only the depth the step started with)",
                      -off, level, one_step_fall)
            : off < 0.0
                ? printf_string(
                      "it rests %.3g m below, and stays: a soft contact's sag, as a spring of "
                      "%.3g N/m under its weight",
                      -off, weight / -off)
                : printf_string(
                      "it rests %.3g m above, and stays: stiffer than its law, or pushed out "
                      "beyond its rest (a contact distance or skin it does not declare)",
                      off);
  return d;
}

double one_step_fall(Law law, double phi, double h, double g) {
  Vec3 x = Vec3::Zero(), v = Vec3::Zero();
  advance(law, phi, h, Vec3(0.0, -g, 0.0), x, v);
  return -x.y();
}

RestingDeparture drift_departure(const Trajectory& run, std::size_t body, double bound) {
  RestingDeparture d;
  if (run.samples() == 0) return d;
  const Vec3 start = run.at(0, body).position;
  for (std::size_t n = 0; n < run.samples(); ++n) {
    const BodyState& s = run.at(n, body);
    const double across = std::hypot(s.position.x() - start.x(), s.position.z() - start.z());
    if (!(across <= bound)) {
      d.step = run.recorded[n];
      d.quantity = "drift";
      d.cause = printf_string(
          "%.3g m across the floor from its start, moving at %.3g m/s along it: its contacts' "
          "friction does not hold it",
          across, std::hypot(s.velocity.x(), s.velocity.z()));
      return d;
    }
  }
  return d;
}

RestingDeparture stillness_departure(const Trajectory& run, std::size_t body, std::int64_t from,
                                     double max_speed, double max_range) {
  RestingDeparture d;
  int reversals = 0;
  double last_vy = 0.0, fastest = 0.0;
  std::int64_t first_reversal = -1, last_reversal = -1;
  Vec3 low = Vec3::Constant(INFINITY), high = Vec3::Constant(-INFINITY);
  for (std::size_t n = 0; n < run.samples(); ++n) {
    if (run.recorded[n] < from) continue;
    const Vec3& v = run.at(n, body).velocity;
    const Vec3& x = run.at(n, body).position;
    low = low.cwiseMin(x);
    high = high.cwiseMax(x);
    fastest = std::max(fastest, v.norm());
    const bool ranges = !((high - low).maxCoeff() <= max_range) || !x.allFinite();
    if (d.step < 0 && (!(v.norm() <= max_speed) || ranges)) d.step = run.recorded[n];
    if (last_vy * v.y() < 0.0) {
      ++reversals;
      if (first_reversal < 0) first_reversal = run.recorded[n];
      last_reversal = run.recorded[n];
    }
    if (v.y() != 0.0) last_vy = v.y();
  }
  if (d.step < 0) return d;
  d.quantity = "stillness";
  d.cause = reversals >= 2
                ? printf_string(
                      "it still moves at up to %.3g m/s, oscillating about its rest (%d "
                      "reversals, a period of about %.3g steps): its contact has not settled",
                      fastest, reversals,
                      2.0 * static_cast<double>(last_reversal - first_reversal) / (reversals - 1))
                : printf_string(
                      "it still moves at up to %.3g m/s without turning back, %.3g m over the "
                      "window: a creep",
                      fastest, (high - low).maxCoeff());
  return d;
}

RestingDeparture path_departure(const Trajectory& run, std::size_t body,
                                const std::vector<double>& path, double tolerance) {
  RestingDeparture d;
  for (std::size_t n = 0; n < run.samples(); ++n) {
    const auto k = static_cast<std::size_t>(run.recorded[n]);
    if (k >= path.size()) break;
    const double off = run.at(n, body).position.y() - path[k];
    if (!(std::abs(off) <= tolerance)) {
      d.step = run.recorded[n];
      d.quantity = "path";
      d.cause =
          printf_string("%.3g m %s its law's height", std::abs(off), off > 0.0 ? "above" : "below");
      return d;
    }
  }
  return d;
}

}  // namespace dropcheck
