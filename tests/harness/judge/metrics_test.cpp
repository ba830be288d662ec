// Tests harness/judge/metrics.cpp: distances between hand-made trajectories whose differences are
// known exactly, sample matching across steps, time to divergence, and observed orders on e =
// C*h^p.
#include "harness/judge/metrics.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <functional>

using namespace dropcheck;

namespace {

// A one-body trajectory at step h over `steps` steps with x(t) = (f(t), 0, 0), v(t) = (g(t), 0, 0).
Trajectory line(
    double h, std::int64_t steps, const std::function<double(double)>& f,
    const std::function<double(double)>& g = [](double) { return 0.0; }) {
  Trajectory t;
  t.engine = "hand-made";
  t.h = h;
  t.steps = steps;
  t.body_names = {"cube"};
  for (std::int64_t n = 0; n <= steps; ++n) {
    const double time = static_cast<double>(n) * h;
    t.recorded.push_back(n);
    t.states.push_back({Vec3(f(time), 0, 0), Vec3(g(time), 0, 0)});
  }
  return t;
}

double zero(double) {
  return 0.0;
}

}  // namespace

TEST_CASE("the metrics of hand-made trajectories are their max, RMS and final distances",
          "[metrics]") {
  // a: x = t, v = 2; b: x = 0, v = 0 over t = 0, 0.25, ..., 1.
  const Trajectory a = line(
      0.25, 4, [](double t) { return t; }, [](double) { return 2.0; });
  const Trajectory b = line(0.25, 4, zero);
  const ErrorStats s = compare(a, b, 0, 0.3);
  CHECK(s.samples == 5);
  CHECK(s.max_dx == 1.0);
  CHECK(s.final_dx == 1.0);
  CHECK(s.final_t == 1.0);
  // RMS of 0, 0.25, 0.5, 0.75, 1: sqrt((0 + 1 + 4 + 9 + 16)/16/5) = sqrt(0.375)
  CHECK(s.rms_dx == Approx(std::sqrt(0.375)).epsilon(1e-15));
  CHECK(s.max_dv == 2.0);
  CHECK(s.rms_dv == Approx(2.0).epsilon(1e-15));
  CHECK(s.final_dv == 2.0);
  CHECK(s.diverged_at == 0.5);  // first sample with |dx| > 0.3
}

TEST_CASE("the metrics say never diverged when the distance stays within the tolerance",
          "[metrics]") {
  const Trajectory a = line(0.1, 10, [](double t) { return 1e-4 * t; });
  const ErrorStats s = compare(a, line(0.1, 10, zero), 0, 1e-3);
  CHECK(s.diverged_at == -1.0);
  CHECK(s.max_dx == Approx(1e-4).epsilon(1e-12));
}

TEST_CASE("the metrics match samples at common times when the steps differ", "[metrics]") {
  // Coarse h = 0.1 (11 samples) against fine h = 0.1/8 (81 samples): the coarse times only.
  const auto x = [](double t) { return t * t; };
  const Trajectory coarse = line(0.1, 10, x),
                   fine = line(0.1 / 8, 80, [](double t) { return t * t + 0.5; });
  const ErrorStats s = compare(coarse, fine, 0, 1.0);
  CHECK(s.samples == 11);
  CHECK(s.max_dx == Approx(0.5).epsilon(1e-12));
  CHECK(s.final_t == Approx(1.0).epsilon(1e-15));
  // The other way round: the fine run is compared at the coarse run's times too.
  CHECK(compare(fine, coarse, 0, 1.0).samples == 11);
}

TEST_CASE("the metrics stop at the last sample of a run that failed early", "[metrics]") {
  Trajectory failed = line(0.1, 10, [](double t) { return t; });
  failed.recorded.resize(6);  // steps 0..5, as a run that went NaN at step 6 keeps
  failed.states.resize(6);
  const ErrorStats s = compare(line(0.1, 10, zero), failed, 0, 1.0);
  CHECK(s.samples == 6);
  CHECK(s.final_t == Approx(0.5).epsilon(1e-15));
  CHECK(s.max_dx == Approx(0.5).epsilon(1e-15));
}

TEST_CASE("the worst-body metrics pick the body farthest apart", "[metrics]") {
  Trajectory a = line(0.5, 2, zero), b = line(0.5, 2, zero);
  for (Trajectory* t : {&a, &b}) {
    t->body_names = {"near", "far"};
    StateBuffer two;
    for (const BodyState& s : t->states) two.insert(two.end(), {s, s});
    t->states = two;
  }
  b.states[5].position.y() = 3.0;  // sample 2, body "far"
  b.states[2].position.y() = 1.0;  // sample 1, body "near"
  CHECK(compare_worst(a, b, 1.0).max_dx == 3.0);
  CHECK(compare(a, b, 0, 1.0).max_dx == 1.0);
}

TEST_CASE("the observed-order metrics recover p from e = C*h^p", "[metrics]") {
  const std::vector<double> h{1.0 / 30, 1.0 / 60, 1.0 / 120, 1.0 / 240};
  for (double p : {1.0, 2.0, 0.5}) {
    std::vector<double> e;
    for (double x : h) e.push_back(0.7 * std::pow(x, p));
    const std::vector<double> orders = observed_orders(h, e);
    REQUIRE(orders.size() == 3);
    for (double o : orders) CHECK(o == Approx(p).epsilon(1e-12));  // measured within 1.1e-16
  }
}

TEST_CASE("the observed-order metrics give NaN where an error is zero", "[metrics]") {
  const std::vector<double> h{0.1, 0.05, 0.025}, e{1e-3, 0.0, 2.5e-4};
  const std::vector<double> orders = observed_orders(h, e);
  REQUIRE(orders.size() == 2);
  CHECK(std::isnan(orders[0]));
  CHECK(std::isnan(orders[1]));
  CHECK(observed_orders(std::vector<double>{0.1}, std::vector<double>{1.0}).empty());
}
