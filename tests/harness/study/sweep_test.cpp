// Tests harness/study/sweep.cpp: a scene's sweep (largest step first, no duplicates, a lone step
// given its half and quarter), the observed order of errors C*h^p read back as p and judged, the
// pre-asymptotic cause named with the phase drift of semi-implicit Euler in closed form, and a
// sweep's extension by halvings: how many it takes to reach the first-order band, and why it stops
// short.
#include "harness/study/sweep.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/number_format.hpp"
#include "harness/core/timestep.hpp"
#include "tests/faulty_engine.hpp"

using Catch::Matchers::Contains;
using namespace dropcheck;
using testing::extreme_scene;

namespace {

Scene with_steps(const Timestep& h, std::vector<Timestep> sweep) {
  Scene s;
  s.name = "steps";
  s.duration = 1.0;
  s.timestep = h;
  s.timesteps = std::move(sweep);
  return s;
}

std::vector<std::string> texts(const std::vector<Timestep>& sweep) {
  std::vector<std::string> out;
  for (const Timestep& t : sweep) out.push_back(t.text);
  return out;
}

}  // namespace

TEST_CASE("a scene's sweep runs largest step first, each step once, the default among them",
          "[sweep]") {
  // 0.016666666666666666 is 1/60 to the last bit: one step, kept as the scene first wrote it.
  const Scene s = with_steps({1.0 / 60.0, "1/60"}, {{1.0 / 120.0, "1/120"},
                                                    {1.0 / 60.0, "1/60"},
                                                    {0.016666666666666666, "0.016666666666666666"},
                                                    {1.0 / 30.0, "1/30"}});
  const std::vector<Timestep> sweep = scene_sweep(s);
  CHECK(texts(sweep) == std::vector<std::string>{"1/30", "1/60", "1/120"});
  CHECK(default_index(sweep, s) == 1);
  // A scene with one step gets its half and quarter, written as the step was.
  CHECK(texts(scene_sweep(with_steps({1.0 / 60.0, "1/60"}, {}))) ==
        std::vector<std::string>{"1/60", "1/120", "1/240"});
  const std::vector<Timestep> decimal = scene_sweep(with_steps({0.01, "0.01"}, {{0.01, "0.01"}}));
  CHECK(texts(decimal) == std::vector<std::string>{"0.01", "0.005", "0.0025"});
  CHECK(decimal[2].seconds == 0.0025);
  // The own-law steps: the default, then the next two of the sweep.
  CHECK(texts(own_law_steps(s)) == std::vector<std::string>{"1/60", "1/30", "1/120"});
}

TEST_CASE("estimate_order reads p back from errors C*h^p and judges it", "[sweep]") {
  const std::vector<double> h{0.1, 0.05, 0.025};
  auto errors = [&](double c, double p) {
    std::vector<double> e;
    for (double x : h) e.push_back(c * std::pow(x, p));
    return e;
  };
  const OrderEstimate first = estimate_order(h, errors(3.0, 1.0), 0.0);
  REQUIRE(first.orders.size() == 2);
  CHECK(first.orders[0] == Approx(1.0).epsilon(1e-12));
  CHECK(first.orders[1] == Approx(1.0).epsilon(1e-12));
  CHECK(first.measurable);
  CHECK(first.first_order);
  CHECK(first.consistent);
  CHECK(first.text ==
        "max |dx| 30 cm, 15 cm, 7.5 cm at h = 0.1, 0.05, 0.025; observed orders "
        "1.000 1.000");
  const OrderEstimate second = estimate_order(h, errors(3.0, 2.0), 0.0);
  CHECK(second.orders[1] == Approx(2.0).epsilon(1e-12));
  CHECK_FALSE(second.first_order);                                       // out of the band 0.9..1.1
  CHECK(second.consistent);                                              // but converging
  const OrderEstimate stuck = estimate_order(h, errors(0.2, 0.0), 0.0);  // an error that stays
  CHECK(stuck.orders[0] == Approx(0.0).margin(1e-12));
  CHECK(stuck.measurable);
  CHECK_FALSE(stuck.consistent);
  // An error at or below the noise floor bends the curve: no order is claimed.
  const OrderEstimate noisy = estimate_order(h, errors(3.0, 1.0), 0.1);
  CHECK_FALSE(noisy.measurable);
  CHECK_FALSE(noisy.first_order);
  CHECK_FALSE(noisy.consistent);
}

TEST_CASE("the pre-asymptotic cause names each product above 0.05, the phase drift in closed form",
          "[sweep]") {
  // stiff_spring (w = 60 rad/s, T = 10 s, undamped) at h = 1/120: w*h = 0.5, and semi-implicit
  // Euler turns by 2*asin(w*h/2) per step instead of w*h, a phase drift over T of
  // w*T*(2*asin(w*h/2)/(w*h) - 1) = 6.43 rad.
  const Scene spring = extreme_scene("stiff_spring");
  const double drift = 60.0 * 10.0 * (2.0 * std::asin(0.25) / 0.5 - 1.0);
  CHECK(drift == Approx(6.4326).epsilon(1e-4));
  CHECK(pre_asymptotic_cause(spring, 1.0 / 120.0) ==
        "omega*h = 0.5 on 'bob', phase drift omega*T*(relative frequency error) = " +
            printf_string("%.3g", drift) + " rad on 'bob' at the sweep's finest step h = 1/120 s");
  // At h = 1/12000 both are small (w*h = 0.005, drift 6.3e-4 rad): the larger is named.
  CHECK(pre_asymptotic_cause(spring, 1.0 / 12000.0) ==
        "omega*h = 0.005 on 'bob' at the sweep's finest step h = 1/12000 s");
  // heavy_drag: k = 60 1/s, k*h = 0.5 at 1/120.
  CHECK(pre_asymptotic_cause(extreme_scene("heavy_drag"), 1.0 / 120.0) ==
        "k*h = 0.5 at the sweep's finest step h = 1/120 s");
  CHECK(pre_asymptotic_cause(with_steps({0.1, "0.1"}, {}), 0.1) ==
        "no rate in the scene (cause not named)");
}

TEST_CASE("a sweep is extended by the halvings its error's h^2 term takes to leave the band",
          "[sweep]") {
  // e(h) = h + 20*h^2: between h and h/2 the order is 1 + log2((1 + 20*h)/(1 + 10*h)), within 1.1
  // once (1 + 20*h)/(1 + 10*h) <= 2^0.1, i.e. h <= 0.00773. From 1/10, 1/20 that is the pair
  // (1/160, 1/320): four halvings, 1/40 to 1/320.
  const Scene scene = with_steps({0.1, "0.1"}, {});
  auto e = [](double h) { return h + 20.0 * h * h; };
  int calls = 0;
  const ExtendedSweep x =
      extend_sweep(scene, {0.1, 0.05}, {e(0.1), e(0.05)}, 0.0, [&](double h, std::string&) {
        ++calls;
        return std::optional<double>(e(h));
      });
  CHECK(x.reached);
  CHECK(x.added == 4);
  CHECK(calls == 4);
  CHECK(x.h.back() == 0.1 / 32.0);
  CHECK(x.estimate.orders.back() <= 1.1);
  CHECK(x.estimate.orders[x.estimate.orders.size() - 2] > 1.1);
}

TEST_CASE("a sweep's extension stops, saying why, at a failed run or the step limit", "[sweep]") {
  const std::vector<double> h{1.0 / 30.0, 1.0 / 60.0}, e{0.3, 0.3};  // order 0: never in band
  Scene scene = with_steps({1.0 / 30.0, "1/30"}, {});
  const ExtendedSweep failed =
      extend_sweep(scene, h, e, 0.0, [](double, std::string& why) -> std::optional<double> {
        why = "it blew up";
        return std::nullopt;
      });
  CHECK_FALSE(failed.reached);
  CHECK(failed.added == 0);
  CHECK(failed.stopped == "at h = 1/120: it blew up");
  // 1e6 s at 1/120 is 1.2e8 steps, beyond the 2e7 a run may take: not even tried.
  scene.duration = 1e6;
  int calls = 0;
  const ExtendedSweep limit = extend_sweep(scene, h, e, 0.0, [&](double, std::string&) {
    ++calls;
    return std::optional<double>(0.3);
  });
  CHECK(calls == 0);
  CHECK(limit.stopped == "h = 1/120 would take more than the step limit");
  // An error that overflowed stays infinite at every finer step: not tried either.
  scene.duration = 1.0;
  const ExtendedSweep overflow =
      extend_sweep(scene, h, {INFINITY, INFINITY}, 0.0, [&](double, std::string&) {
        ++calls;
        return std::optional<double>(INFINITY);
      });
  CHECK(calls == 0);
  CHECK(overflow.stopped == "the error at h = 1/60 is inf, which no finer step makes finite");
}

TEST_CASE("a step is written 1/N when it is one, and two steps are one to 1e-12", "[sweep]") {
  CHECK(step_text(1.0 / 480.0) == "1/480");
  CHECK(step_text(0.5) == "1/2");
  CHECK(step_text(0.3) == "0.3");
  CHECK(step_text(0.0123456) == "0.01235");
  CHECK(same_step(0.1, 0.1 * (1.0 + 1e-13)));
  CHECK_FALSE(same_step(0.1, 0.1 * (1.0 + 1e-11)));
}
