// Tests harness/study/phase_drift.cpp and its use by the convergence check: the phase drift of
// semi-implicit Euler on an undamped spring, derived from the law's eigenvalues, bounds the law's
// error against the closed form; a long run whose sweep that drift keeps out of the first-order
// band is a LIMIT naming it; errors the drift does not predict, and engines that leave their law
// (a frequency off by 0.05%, a spring of the wrong sign), still FAIL.
#include "harness/study/phase_drift.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "harness/core/registry.hpp"
#include "harness/judge/metrics.hpp"
#include "harness/oracles/analytic.hpp"
#include "harness/oracles/discrete_law.hpp"
#include "harness/scene/scene_loader.hpp"
#include "harness/study/checks.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;

namespace {

// long_run in small: an undamped spring of omega = 2*pi rad/s for 40 s, thrown sideways so the
// orbit is an ellipse in 3-D. Drift omega*T*(omega*h)^2/24 = 0.46 rad at h = 1/30, still as large
// as the law's first-order phase offset omega*h/2 at h = 1/120: its sweep is not first order.
constexpr const char* kLongSpring = R"(
duration = 40.0
timestep = "1/30"
[world]
gravity = [0.0, -9.8, 0.0]
[[body]]
name = "bob"
position = [0.0, 9.0, 0.0]
velocity = [0.6, 0.0, 0.3]
[[force]]
bodies = ["bob"]
spring = { anchor = [0.0, 10.0, 0.0], stiffness = 39.47841760435743, rest_length = 0.0 }
)";

Scene long_spring(double stiffness_factor = 1.0) {
  Scene s = parse_scene(kLongSpring, "long_spring.toml");
  std::get<Spring>(s.forces[0].law).stiffness *= stiffness_factor;
  return s;
}

const Law kOurs = DampingOrder::AfterForces;

// The worst error of `law` iterated on `run_on` against the closed form of `truth`, at each step.
std::vector<double> law_errors(const Scene& run_on, const Scene& truth,
                               const std::vector<double>& h) {
  std::vector<double> e;
  for (double step : h)
    e.push_back(compare_worst(predict_discrete(kOurs, run_on, step),
                              *analytic_trajectory(truth, step), truth.tolerance)
                    .max_dx);
  return e;
}

const std::vector<double> kSweep{1.0 / 30, 1.0 / 60, 1.0 / 120, 1.0 / 240};

// ours-f64 with its forces scaled by `gain` (-1: a spring of the wrong sign, and gravity too;
// 1.001: a frequency 0.05% off), still declaring its law, as a mis-mapped adapter would.
class ScaledForces final : public Engine {
 public:
  explicit ScaledForces(double gain) : gain_(gain), inner_(make_engine("ours-f64")) {}
  EngineInfo info() const override {
    EngineInfo i = inner_->info();
    i.name = "scaled";
    return i;
  }
  void load(const Scene& scene, double h) override { inner_->load(scene, h); }
  void set_forces(std::span<const Vec3> f) override {
    scaled_.assign(f.begin(), f.end());
    for (Vec3& x : scaled_) x *= gain_;
    inner_->set_forces(scaled_);
  }
  void step() override { inner_->step(); }
  void read(std::span<BodyState> out) const override { inner_->read(out); }

 private:
  double gain_;
  std::vector<Vec3> scaled_;
  std::unique_ptr<Engine> inner_;
};

EngineFactory scaled(double gain) {
  return [gain] { return std::make_unique<ScaledForces>(gain); };
}
EngineFactory ours_f64() {
  return [] { return make_engine("ours-f64"); };
}

// Cap on the steps a sweep extension may add in these tests: h = 1/240 (9600 steps), not 1/480.
constexpr std::int64_t kSmallCap = 10000;

}  // namespace

TEST_CASE("the drift derived from the law's eigenvalues is omega*T*(omega*h)^2/24 to leading order",
          "[phase_drift]") {
  const Scene s = long_spring();
  const double w = 2.0 * std::numbers::pi;
  for (double h : kSweep) {
    const std::vector<DriftPrediction> p = predict_drift(s, kOurs, h);
    REQUIRE(p.size() == 1);
    CHECK(p[0].body == "bob");
    CHECK(p[0].theta == Approx(2.0 * std::asin(w * h / 2.0)).epsilon(1e-12));
    CHECK(p[0].drift == Approx(w * 40.0 * (w * h) * (w * h) / 24.0).epsilon(0.02));
    CHECK(p[0].offset == Approx(p[0].semi_axis * w * h / 2.0).epsilon(0.1));
  }
}

TEST_CASE("the drift band holds the error of the iterated law at every step of a sweep",
          "[phase_drift]") {
  const Scene s = long_spring();
  const std::vector<double> e = law_errors(s, s, kSweep);
  for (std::size_t k = 0; k < kSweep.size(); ++k) {
    const DriftPrediction p = predict_drift(s, kOurs, kSweep[k]).at(0);
    INFO("h = " << kSweep[k] << ": " << p.lower << " <= " << e[k] << " <= " << p.upper);
    CHECK(e[k] >= p.lower);
    CHECK(e[k] <= p.upper);
  }
}

TEST_CASE("the drift explains a long run's sweep of the law and names the cause", "[phase_drift]") {
  const Scene s = long_spring();
  const DriftVerdict v = judge_drift(s, kOurs, kSweep, law_errors(s, s, kSweep), 0.0);
  INFO(v.limit_text() << " | " << v.sentence());
  CHECK(v.applies);
  CHECK(v.explained);
  CHECK_THAT(v.limit_text(),
             Contains("pre-asymptotic: the phase drift of semi-implicit Euler over 40 s "
                      "on 'bob' is 0.462 rad at h = 1/30"));
  CHECK_THAT(v.sentence(), Contains(": within the band"));
}

TEST_CASE("the drift verdict holds the drifting body, its band and the error at every step",
          "[phase_drift]") {
  const Scene s = long_spring();
  const std::vector<double> e = law_errors(s, s, kSweep);
  const DriftVerdict v = judge_drift(s, kOurs, kSweep, e, 0.0);
  CHECK(v.law == kOurs);
  CHECK(v.body == "bob");
  CHECK(v.duration == Approx(40.0));
  CHECK(v.omega == Approx(2.0 * std::numbers::pi));
  CHECK(v.first_order_edge() == Approx(12.0 / (v.omega * v.omega * 40.0)));
  REQUIRE(v.steps.size() == kSweep.size());
  for (std::size_t k = 0; k < kSweep.size(); ++k) {
    const DriftBand& b = v.steps[k];
    const DriftPrediction p = predict_drift(s, kOurs, kSweep[k]).at(0);
    CHECK(b.h == kSweep[k]);
    CHECK(b.error == e[k]);
    CHECK(b.drift == p.drift);
    CHECK(b.lower == p.lower);
    CHECK(b.upper == p.upper);
    CHECK(b.within);
  }
  CHECK(v.steps.front().drift == Approx(0.462).epsilon(0.002));
  // Errors from a frequency 0.05% off leave the band at some step, and that step says so.
  const DriftVerdict off =
      judge_drift(s, kOurs, kSweep, law_errors(long_spring(1.001), s, kSweep), 0.0);
  CHECK(std::any_of(off.steps.begin(), off.steps.end(),
                    [](const DriftBand& b) { return !b.within; }));
  // Where it does not apply, nothing is measured.
  const DriftVerdict none = judge_drift(load_scene("scenarios/free_fall.toml"), kOurs, kSweep,
                                        std::vector<double>(4, 1.0), 0.0);
  CHECK_FALSE(none.applies);
  CHECK(none.steps.empty());
  CHECK(none.sentence().empty());
}

TEST_CASE("errors from a frequency error of the wrong size are not explained by the drift",
          "[phase_drift]") {
  const Scene s = long_spring();
  // The law run with a stiffness 0.1% off: its frequency error is the law's plus 5e-4.
  const DriftVerdict off =
      judge_drift(s, kOurs, kSweep, law_errors(long_spring(1.001), s, kSweep), 0.0);
  INFO(off.sentence());
  CHECK(off.applies);
  CHECK_FALSE(off.explained);
  CHECK(off.limit_text().empty());
  CHECK_THAT(off.sentence(), Contains("OUTSIDE the band at h = "));
  // No error at all (an engine exact where its law drifts) is not the law either.
  const DriftVerdict none = judge_drift(s, kOurs, kSweep, std::vector<double>(4, 0.0), 1e-9);
  CHECK_FALSE(none.explained);
}

TEST_CASE("the drift does not apply to a damped spring, explicit Euler or free flight",
          "[phase_drift]") {
  const Scene drag = load_scene("scenarios/extreme/stiff_spring_drag.toml");
  CHECK(predict_drift(drag, kOurs, 1.0 / 60).empty());
  const Law explicit_euler{DampingOrder::AfterForces, PositionUpdate::Explicit};
  CHECK(predict_drift(long_spring(), explicit_euler, 1.0 / 60).empty());
  CHECK(predict_drift(load_scene("scenarios/free_fall.toml"), kOurs, 1.0 / 60).empty());
  const DriftVerdict v = judge_drift(drag, kOurs, kSweep, std::vector<double>(4, 1.0), 0.0);
  CHECK_FALSE(v.applies);
}

TEST_CASE("a long run that follows its law, its sweep kept out of band by the drift, is a LIMIT",
          "[phase_drift][checks]") {
  const CheckResult r = check_divergence(long_spring(), ours_f64(), ours_f64(), kSmallCap);
  INFO(r.limit << " | " << r.message);
  CHECK(r.passed);
  CHECK_THAT(r.limit, Contains("pre-asymptotic: the phase drift of semi-implicit Euler"));
  CHECK_THAT(r.message, Contains("extended by 1 halving, stopped") && Contains("measured") &&
                            Contains(": within the band"));
}

TEST_CASE("an engine whose frequency is 0.05% off, or whose spring pushes, still FAILs",
          "[phase_drift][checks]") {
  for (double gain : {1.001, -1.0}) {
    const CheckResult r = check_divergence(long_spring(), scaled(gain), scaled(gain), kSmallCap);
    INFO("gain " << gain << ": " << r.message);
    CHECK_FALSE(r.passed);
    CHECK(r.limit.empty());
    CHECK_THAT(r.message, Contains("departs from its own law"));
  }
}
