// Classification of one run: run status, growth, tunnelling, frozen coordinates, speed clamps.
// Each detector lives with its reasoning: growth in stability_growth.cpp, tunnelling and frozen
// coordinates in stability_motion.cpp; the run status and clamps here.
#include "harness/judge/stability_classify.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

#include "harness/core/number_format.hpp"
#include "harness/judge/stability_growth.hpp"
#include "harness/judge/stability_motion.hpp"

namespace dropcheck {

namespace stability_detail {

BodyLaw body_law(const Scene& scene, std::size_t index) {
  const Body& b = scene.bodies[index];
  BodyLaw law;
  law.accel = scene.world.gravity;
  Vec3 weighted = Vec3::Zero();
  for (const Force& f : scene.forces) {
    if (std::find(f.bodies.begin(), f.bodies.end(), index) == f.bodies.end()) continue;
    if (const auto* c = std::get_if<ConstantForce>(&f.law)) {
      law.accel += c->force / b.mass;
      continue;
    }
    const Spring& s = std::get<Spring>(f.law);
    law.nonlinear = law.nonlinear || s.rest_length != 0.0;
    law.stiffness += s.stiffness;
    law.dashpot += s.damping;
    weighted += s.stiffness * s.anchor;
  }
  if (law.stiffness > 0.0) law.anchor = weighted / law.stiffness;
  return law;
}

double float_spacing(double x, Scalar scalar) {
  const double ax = std::abs(x);
  if (scalar == Scalar::f32) {
    const float f = static_cast<float>(ax);
    return static_cast<double>(std::nextafter(f, INFINITY)) - static_cast<double>(f);
  }
  return std::nextafter(ax, INFINITY) - ax;
}

}  // namespace stability_detail

namespace {

void add_status(const Trajectory& run, std::vector<Failure>& out) {
  if (run.status == RunStatus::engine_error)
    out.push_back({FailureMode::engine_error, "", run.failed_step,
                   printf_string("engine error at step %lld: %s",
                                 static_cast<long long>(run.failed_step), run.failure.c_str())});
  else if (run.status == RunStatus::non_finite)
    out.push_back({FailureMode::non_finite, "", run.failed_step, run.failure});
  else if (run.status != RunStatus::ok)  // crashed, timed out, refused, out of memory
    out.push_back({FailureMode::engine_error, "", run.failed_step,
                   std::string(to_string(run.status)) + ": " + run.failure});
}

// The sample at or after `step` (the last one if none).
std::size_t sample_at(const Trajectory& run, std::int64_t step) {
  auto it = std::lower_bound(run.recorded.begin(), run.recorded.end(), step);
  return it == run.recorded.end() ? run.samples() - 1
                                  : static_cast<std::size_t>(it - run.recorded.begin());
}

// Speed clamps are counted by the runner (Engine::speed_clamped); name the fastest body at the
// first clamped step and its travel per step, the quantity engines limit (Box2D: 2 m per step),
// and in a turning run the fastest turn per step too (turns are clamped as well).
void add_clamp(const Scene& scene, const Trajectory& run, std::vector<Failure>& out) {
  if (run.clamped_steps == 0) return;
  const std::size_t s = sample_at(run, run.first_clamped_step);
  std::size_t fastest = 0;
  double speed = -1.0;
  for (std::size_t b = 0; b < run.bodies(); ++b) {
    if (scene.bodies[b].is_static) continue;
    const double v = run.at(s, b).velocity.norm();
    if (v > speed) speed = v, fastest = b;
  }
  std::string what = printf_string(
      "speed clamped by the engine on %lld of %lld steps, first at step %lld "
      "(t = %.4g s), where body '%s' moves %.3g m per step (|v| = %.4g m/s)",
      static_cast<long long>(run.clamped_steps), static_cast<long long>(run.steps),
      static_cast<long long>(run.first_clamped_step),
      static_cast<double>(run.first_clamped_step) * run.h, run.body_names[fastest].c_str(),
      speed * run.h, speed);
  // A turning run: the clamp may be on the turn (Bullet: pi/4 per step, Box2D: pi/2); name the
  // fastest turn as well.
  if (run.rotates && s < run.samples()) {
    std::size_t spinning = 0;
    double w = -1.0;
    for (std::size_t b = 0; b < run.bodies(); ++b)
      if (!scene.bodies[b].is_static && run.rotation_at(s, b).angular_velocity.norm() > w)
        w = run.rotation_at(s, b).angular_velocity.norm(), spinning = b;
    what += printf_string(", and body '%s' turns by |w|*h = %.3g rad per step (|w| = %.4g rad/s)",
                          run.body_names[spinning].c_str(), w * run.h, w);
  }
  out.push_back({FailureMode::clamped, run.body_names[fastest], run.first_clamped_step, what});
}

}  // namespace

const char* to_string(FailureMode mode) {
  switch (mode) {
    case FailureMode::engine_error:
      return "engine error";
    case FailureMode::non_finite:
      return "NaN/Inf";
    case FailureMode::unbounded_growth:
      return "unbounded growth";
    case FailureMode::tunnelled:
      return "tunnelled";
    case FailureMode::frozen:
      return "frozen";
    case FailureMode::clamped:
      return "speed clamped";
    case FailureMode::off_contact_law:
      return "off contact law";
  }
  return "?";
}

std::string engine_label(const std::string& engine, Scalar scalar) {
  return engine + " (" + to_string(scalar) + ")";
}

Verdict classify_run(const Scene& scene, const Trajectory& run, Scalar scalar,
                     const ClassifyOptions& options) {
  Verdict v;
  add_status(run, v.failures);
  if (run.samples() > 0) {
    stability_detail::find_growth(scene, run, options, v.failures);
    if (scene.world.contacts) stability_detail::find_tunnelling(scene, run, v.failures);
    stability_detail::find_frozen(scene, run, scalar, options, v.failures);
    add_clamp(scene, run, v.failures);
  }
  std::stable_sort(v.failures.begin(), v.failures.end(), [](const Failure& a, const Failure& b) {
    return a.mode != b.mode ? a.mode < b.mode : a.step < b.step;
  });
  return v;
}

}  // namespace dropcheck
