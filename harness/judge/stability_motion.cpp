// Failures of motion: a body that passed through (or sank into) a body it started above, and a
// coordinate frozen by precision while the physics says it moves. y is up (docs/design.md).
#include "harness/judge/stability_motion.hpp"

#include <algorithm>
#include <cmath>

#include "harness/core/number_format.hpp"
#include "harness/oracles/analytic.hpp"

namespace dropcheck::stability_detail {
namespace {

// Boxes a and b overlap in the horizontal plane (x and z), centres ca and cb.
bool overlap_xz(const Body& a, const Vec3& ca, const Body& b, const Vec3& cb) {
  return std::abs(ca.x() - cb.x()) < a.half_extents.x() + b.half_extents.x() &&
         std::abs(ca.z() - cb.z()) < a.half_extents.z() + b.half_extents.z();
}

// Body a (dynamic) with body b under it at the start: what went wrong at sample s, or "".
// Resting on b, a's centre sits hy_a + hy_b above b's. Passed: a's centre ends less than half that
// above b's (level with it, or below), still over b's starting footprint (b may have been pushed
// aside: a heavy cube squeezing a light one out). Sank: over b and deeper into it than a quarter of
// the thinner box (engines rest within millimetres: docs/engines.md section 5).
std::string passage(const Body& a, const Body& b, const Trajectory& run, std::size_t ia,
                    std::size_t ib, std::size_t s) {
  const Vec3 ca = run.at(s, ia).position, cb = run.at(s, ib).position, cb0 = run.at(0, ib).position;
  const double rest = a.half_extents.y() + b.half_extents.y(), sep = ca.y() - cb.y();
  if (sep < 0.5 * rest && overlap_xz(a, ca, b, cb0)) {
    const std::string aside =
        overlap_xz(a, ca, b, cb)
            ? std::string()
            : printf_string(", which was pushed aside to x = %.4g, z = %.4g", cb.x(), cb.z());
    return printf_string(
        "ended %s '%s'%s (centres %.4g m apart vertically, %.4g m when resting on it)",
        sep < 0.0 ? "below" : "level with", b.name.c_str(), aside.c_str(), sep, rest);
  }
  const double depth = rest - sep, limit = 0.5 * std::min(a.half_extents.y(), b.half_extents.y());
  if (overlap_xz(a, ca, b, cb) && depth > limit)
    return printf_string("sank %.4g m into '%s' (more than a quarter of the thinner box, %.4g m)",
                         depth, b.name.c_str(), limit);
  return {};
}

void check_pair(const Scene& scene, const Trajectory& run, std::size_t ia, std::size_t ib,
                std::vector<Failure>& out) {
  const Body &a = scene.bodies[ia], &b = scene.bodies[ib];
  const Vec3 a0 = run.at(0, ia).position, b0 = run.at(0, ib).position;
  // Started above: a's bottom at or above b's top (1 mm of slack for a resting start), over it.
  const bool above = a0.y() - a.half_extents.y() >= b0.y() + b.half_extents.y() - 1e-3;
  if (!above || !overlap_xz(a, a0, b, b0)) return;
  const std::size_t last = run.samples() - 1;
  const std::string how = passage(a, b, run, ia, ib, last);
  if (how.empty()) return;
  std::size_t s = 0;  // the first sample where it showed, for the step and the speed then
  while (s < last && passage(a, b, run, ia, ib, s).empty()) ++s;
  const double travel = run.at(s, ia).velocity.norm() * run.h;
  out.push_back(
      {FailureMode::tunnelled, a.name, run.recorded[s],
       printf_string("body '%s' %s; it started above that %s body; from step %lld, moving %.3g m "
                     "per step (|v|*h) against %.3g m of both boxes' heights",
                     a.name.c_str(), how.c_str(), b.is_static ? "static" : "dynamic",
                     static_cast<long long>(run.recorded[s]), travel,
                     2.0 * (a.half_extents.y() + b.half_extents.y()))});
}

}  // namespace

void find_tunnelling(const Scene& scene, const Trajectory& run, std::vector<Failure>& out) {
  for (std::size_t a = 0; a < scene.bodies.size(); ++a) {
    if (scene.bodies[a].is_static) continue;
    const std::size_t before = out.size();
    for (std::size_t b = 0; b < scene.bodies.size() && out.size() == before; ++b)
      if (b != a) check_pair(scene, run, a, b, out);
  }
}

namespace {

const char* kAxis[] = {"x", "y", "z"};

// One stretch of samples [first, last] over which coordinate c of a body kept the same value.
struct Stretch {
  std::size_t first = 0, last = 0;
  double path_engine = 0.0;   // sum of |v_c|*h over its steps, with the engine's own velocity (m)
  double path_physics = 0.0;  // the same with the analytic velocity (m); -1 when there is none
  double min_vh = INFINITY, max_vh = 0.0;  // the engine's |v_c|*h per step, range over the stretch
};

Stretch measure_motion(const Trajectory& run, const std::vector<BodyState>* exact, std::size_t i,
                       int c, std::size_t first, std::size_t last) {
  Stretch st{first, last, 0.0, exact ? 0.0 : -1.0};
  for (std::size_t s = first + 1; s <= last; ++s) {
    const double steps = static_cast<double>(run.recorded[s] - run.recorded[s - 1]);
    const double vh = std::abs(run.at(s, i).velocity[c]) * run.h;
    st.path_engine += vh * steps;
    if (exact) st.path_physics += std::abs((*exact)[s].velocity[c]) * run.h * steps;
    st.min_vh = std::min(st.min_vh, vh);
    st.max_vh = std::max(st.max_vh, vh);
  }
  return st;
}

std::string frozen_sentence(const Trajectory& run, std::size_t i, int c, const Stretch& st,
                            double spacing, Scalar scalar) {
  const double x = run.at(st.first, i).position[c];
  const double moved = st.path_physics >= 0.0 ? st.path_physics : st.path_engine;
  // Rounding explains it when every step's v*h is below half the spacing while their sum says the
  // body should have moved; otherwise the engine itself held the body.
  const bool rounding = st.max_vh < 0.5 * spacing && st.path_engine > 0.5 * spacing;
  std::string why =
      rounding
          ? printf_string(
                "v*h = %.2g m to %.2g m per step is below half the %s spacing %.2g m at %.6g m",
                st.min_vh, st.max_vh, scalar == Scalar::f32 ? "float" : "double", 0.5 * spacing,
                std::abs(x))
          : printf_string(
                "its own v*h (%.2g m to %.2g m per step, %.2g m in all, against half the spacing "
                "%.2g m) does not explain it: the engine held it (sleeping or a threshold)",
                st.min_vh, st.max_vh, st.path_engine, 0.5 * spacing);
  return printf_string(
      "body '%s': position frozen at %s = %.6f from step %lld to step %lld while it should "
      "have moved %.3g m: %s",
      run.body_names[i].c_str(), kAxis[c], x, static_cast<long long>(run.recorded[st.first] + 1),
      static_cast<long long>(run.recorded[st.last]), moved, why.c_str());
}

// Frozen by precision: coordinate c stays bit-identical over at least frozen_steps steps although
// the physics says it moves more than half a spacing of the engine's scalar there (so the correctly
// rounded true position would differ from the frozen one) and more than the scene's tolerance (the
// divergence that matters to the scene: a body settling at rest in double "freezes" while the exact
// solution still creeps by 1e-14 m, measured on long_run). "The physics" is the analytic solution
// where one exists (it also catches an engine that stops a body: sleeping). With contacts there is
// none; then the engine's own velocity must say so AND every step's v*h must lie below the
// spacing: only rounding explains that (a resting box's solver velocity does not count).
bool frozen_in(const Trajectory& run, const std::vector<BodyState>* exact, std::size_t i, int c,
               Scalar scalar, double tolerance, const ClassifyOptions& o,
               std::vector<Failure>& out) {
  std::size_t first = 0;
  for (std::size_t s = 1; s <= run.samples(); ++s) {
    if (s < run.samples() && run.at(s, i).position[c] == run.at(first, i).position[c]) continue;
    const std::size_t last = s - 1;
    if (run.recorded[last] - run.recorded[first] >= o.frozen_steps) {
      const Stretch st = measure_motion(run, exact, i, c, first, last);
      const double spacing = float_spacing(run.at(first, i).position[c], scalar);
      const double lost = std::max(0.5 * spacing, tolerance);
      const bool moves =
          exact ? st.path_physics > lost : st.path_engine > lost && st.max_vh < spacing;
      if (moves) {
        out.push_back({FailureMode::frozen, run.body_names[i], run.recorded[first] + 1,
                       frozen_sentence(run, i, c, st, spacing, scalar)});
        return true;
      }
    }
    first = s;
  }
  return false;
}

}  // namespace

void find_frozen(const Scene& scene, const Trajectory& run, Scalar scalar, const ClassifyOptions& o,
                 std::vector<Failure>& out) {
  const bool has_exact = analytic_unavailable(scene).empty();
  std::vector<BodyState> exact;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].is_static) continue;
    exact.clear();
    if (has_exact)
      for (std::size_t s = 0; s < run.samples(); ++s)
        exact.push_back(analytic_state(scene, i, run.time(s)));
    for (int c = 0; c < 3; ++c)
      if (frozen_in(run, has_exact ? &exact : nullptr, i, c, scalar, scene.tolerance, o, out))
        break;
  }
}

}  // namespace dropcheck::stability_detail
