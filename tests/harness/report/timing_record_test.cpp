// Tests harness/report/timing_record.cpp: timings.json reads back exactly, bad records are refused
// naming the file and key, and two records are compared cell by cell (the two-run figure of the
// report's "Timing reproducibility").
#include "harness/report/timing_record.hpp"

#include <catch2/catch.hpp>

#include "harness/core/input_error.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;

namespace {

// A cell of 8 samples whose minimum is `min_ms` (the others up to 1.7 x it), with a calibration
// loop of 1 ms in every round.
TimedCell timed(const std::string& scene, const std::string& engine, const std::string& h,
                double min_ms) {
  TimedCell c{scene, engine, h, {}, {}, {}, 4, 2};
  for (int i = 0; i < 8; ++i) {
    c.full_ms.push_back(min_ms * (1.0 + 0.1 * ((i * 3) % 8)));
    c.bare_ms.push_back(0.5 * min_ms);
    c.calibration_ms.push_back(1.0 + 0.01 * i);
  }
  return c;
}

// The machine the records of these tests were timed on.
const Machine kHere{
    "CPU x",           "family 6, model 207, stepping 2", "L1d 48K, L2 2048K", 2, "6.1.0",
    "00000000000000aa"};

std::string parse_error(const std::string& text) {
  try {
    parse_timing_record(text, "out/timings.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

TEST_CASE("a timings record reads back exactly what was written, every sample", "[timing]") {
  const TimingRecord r{"abc1234",
                       "CPU \"x\", 2 logical",
                       {timed("wind", "ours", "1/60", 0.1 / 3), timed("a,b", "ode", "0.01", 1e-300),
                        timed("wind", "bullet", "1/60", 12345.678901234567)},
                       kHere};
  const TimingRecord back = parse_timing_record(timing_json(r), "timings.json");
  CHECK(back.commit == r.commit);
  CHECK(back.cpu == r.cpu);
  REQUIRE(back.cells.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) {
    const TimedCell &a = r.cells[i], &b = back.cells[i];
    CHECK(std::tie(a.scene, a.engine, a.h, a.replicas, a.repeats) ==
          std::tie(b.scene, b.engine, b.h, b.replicas, b.repeats));
    CHECK(std::tie(a.full_ms, a.bare_ms, a.calibration_ms) ==
          std::tie(b.full_ms, b.bare_ms, b.calibration_ms));
  }
  CHECK(parse_timing_record(timing_json({"c", "cpu", {}, kHere}), "t").cells.empty());
}

TEST_CASE("a cell's figures are statistics of its samples, alone or over the calibration's",
          "[timing]") {
  const TimedCell c = timed("s", "ours", "1/60", 2.0);  // samples 2.0 .. 3.4, calibration 1.0 ..
  CHECK(c.value({Statistic::min, false}) == 2.0);
  CHECK(c.value({Statistic::min, true}) == 2.0);              // over the calibration's minimum, 1.0
  CHECK(c.value({Statistic::median, false}) == Approx(2.7));  // 2.6 and 2.8
  CHECK(c.value({Statistic::median, true}) == Approx(2.7 / 1.035));
  CHECK(c.value({}) == c.value({kHeadline, false}));
  CHECK(TimedCell{}.value({}) == 0.0);
  CHECK(TimedCell{}.value({kHeadline, true}) == 0.0);
}

TEST_CASE("a bad timings record is refused naming the file, the key and the problem", "[timing]") {
  const std::string cell =
      R"({"scene":"s","engine":"e","h":"1/60","replicas":1,"repeats":1,"samples_ms":[1,2],)"
      R"("bare_samples_ms":[1,1],"calibration_ms":[1,1]})";
  const auto with = [&](const std::string& c) {
    return R"({"commit":"c","cpu":"x","cells":[)" + cell + "," + c + "]}";
  };
  const auto edited = [&](const std::string& from, const std::string& to) {
    std::string c = cell;
    c.replace(c.find(from), from.size(), to);
    return with(c);
  };
  CHECK(parse_error(with(cell)) == "(accepted)");
  CHECK_THAT(parse_error("{\"commit\": "),
             Contains("out/timings.json") && Contains("not a timings"));
  CHECK_THAT(parse_error("[1, 2]"), Contains("expected a JSON object"));
  CHECK_THAT(parse_error(R"({"commit":"c","cpu":"x","cells":[{"samples_ms":[1e999]}]})"),
             Contains("not a timings record") && Contains("number overflow"));
  CHECK_THAT(parse_error(R"({"commit":"c","cpu":"x"})"),
             Contains("cells: required key is missing"));
  CHECK_THAT(parse_error(R"({"commit":"c","cpu":"x","cells":{}})"),
             Contains("cells: expected an array, got object"));
  CHECK_THAT(parse_error(edited(R"("samples_ms":[1,2],)", "")),
             Contains("cells[1].samples_ms: required key is missing"));
  CHECK_THAT(parse_error(edited(R"("samples_ms":[1,2])", R"("samples_ms":[1,-2])")),
             Contains("cells[1].samples_ms[1]: expected a finite number >= 0"));
  CHECK_THAT(parse_error(edited(R"("samples_ms":[1,2])", R"("samples_ms":[])")),
             Contains("cells[1].samples_ms: expected an array of 1 to 4096 numbers"));
  CHECK_THAT(parse_error(edited(R"("calibration_ms":[1,1])", R"("calibration_ms":[1])")),
             Contains("cells[1].samples_ms") && Contains("differ in length"));
  CHECK_THAT(parse_error(edited(R"("h":"1/60")", R"("h":60)")),
             Contains("cells[1].h: expected a string, got number"));
  CHECK_THAT(parse_error(edited(R"("replicas":1)", R"("replicas":1.5)")),
             Contains("cells[1].replicas: expected a whole number"));
  CHECK_THAT(parse_error(with("7")), Contains("cells[1]: expected an object, got number"));
}

TEST_CASE("two timing records are compared on the cells both hold, once each", "[timing]") {
  const TimingRecord before{"a",
                            "cpu",
                            {timed("s", "ours", "1/60", 1.0), timed("s", "ode", "1/60", 2.0),
                             timed("s", "bullet", "1/60", 3.0), timed("s", "box2d", "1/60", 1.0),
                             timed("s", "box2d", "1/60", 1.0), timed("t", "ours", "1/60", 1.0)},
                            kHere};
  const TimingRecord now{"a",
                         "cpu",
                         {timed("s", "ours", "1/60", 1.09),    // +9 %: agrees
                          timed("s", "ode", "1/60", 1.6),      // 2 / 1.6 - 1 = 25 %
                          timed("s", "bullet", "1/60", 3.03),  // +1 %
                          timed("s", "box2d", "1/60", 1.0),    // twice in `before`: left out
                          timed("s", "ours", "1/120", 5.0)},   // not in `before`: left out
                         kHere};
  const TimingComparison c = compare_timings(before, now, {}, 0.10, 2);
  CHECK(c.cells == 3);
  CHECK(c.agree == 2);
  CHECK(c.median_moved == Approx(0.09));
  REQUIRE(c.worst.size() == 2);
  CHECK(c.worst[0].engine == "ode");
  CHECK(c.worst[0].before == 2.0);
  CHECK(c.worst[0].now == 1.6);
  CHECK(c.worst[0].moved == Approx(0.25));
  CHECK(c.worst[1].engine == "ours");
  CHECK(compare_timings(now, now).agree == 5);
  CHECK(compare_timings(now, now).worst.size() == 5);  // keep = 5 by default
}

TEST_CASE("the side-by-side ratio cancels a machine that is slower for both", "[timing]") {
  TimedCell a = timed("s", "ode", "1/60", 2.0), b = a;
  for (double& x : b.full_ms) x *= 1.3;  // the whole machine 30 % slower in the second run
  for (double& x : b.calibration_ms) x *= 1.3;
  const TimingRecord before{"a", "cpu", {a}, kHere}, now{"a", "cpu", {b}, kHere};
  CHECK(compare_timings(before, now, {kHeadline, false}).agree == 0);
  CHECK(compare_timings(before, now, {kHeadline, true}).agree == 1);
}

TEST_CASE("the slowdown alert flags a cell whose headline rose past its engine's threshold",
          "[timing]") {
  const double t = slowdown_threshold("ode");
  REQUIRE(t > 0.0);
  CHECK(t < 0.20);  // a 20 % slowdown must be caught
  const TimingRecord before{"a",
                            "cpu",
                            {timed("s", "ode", "1/60", 1.0), timed("s", "ode", "1/120", 1.0),
                             timed("s", "ours", "1/60", 1.0)},
                            kHere};
  const TimingRecord now{"b",
                         "cpu",
                         {timed("s", "ode", "1/60", 1.0 + 0.5 * t),  // noise: not flagged
                          timed("s", "ode", "1/120", 1.20),          // a 20 % slowdown
                          timed("s", "ours", "1/60", 0.5)},          // faster: not flagged
                         kHere};
  const std::vector<Slowdown> s = slowdowns(before, now);
  REQUIRE(s.size() == 1);
  CHECK(s[0].cell.h == "1/120");
  CHECK(s[0].cell.moved == Approx(0.20));
  CHECK(s[0].threshold == t);
  CHECK(s[0].engine_median == Approx((0.5 * t + 0.20) / 2));  // the median of two: their mean
  CHECK(slowdowns(now, now).empty());
  // One noisy cell alone, its engine's other cells unmoved: its engine did not slow, no flag.
  TimingRecord three = before;
  three.cells.push_back(timed("s", "ode", "1/240", 1.0));
  TimingRecord noisy = three;
  noisy.cells[1] = timed("s", "ode", "1/120", 1.30);
  CHECK(slowdowns(three, noisy).empty());
  // The engine slowed, every cell 20 %: each is flagged.
  TimingRecord slowed = three;
  for (TimedCell& c : slowed.cells)
    if (c.engine == "ode") c = timed("s", "ode", c.h, 1.20);
  CHECK(slowdowns(three, slowed).size() == 3);
  CHECK(slowdown_threshold("exec:my-engine") >= slowdown_threshold("ode"));
  // The whole machine 30 % slower (the calibration loop too): the ratio holds, nothing is flagged.
  TimingRecord slower_machine = before;
  for (TimedCell& c : slower_machine.cells) {
    for (double& x : c.full_ms) x *= 1.3;
    for (double& x : c.calibration_ms) x *= 1.3;
  }
  CHECK(slowdowns(before, slower_machine).empty());
  // Cells timed another way (other copies, repeats or number of samples) are not judged.
  TimingRecord other_work = now;
  for (TimedCell& c : other_work.cells) c.replicas *= 2;
  std::size_t judged = 99;
  CHECK(slowdowns(before, other_work, &judged).empty());
  CHECK(judged == 0);
  slowdowns(before, now, &judged);
  CHECK(judged == 3);
  // The same cells timed on another machine, or by a record that does not say where: none judged.
  for (const Machine& elsewhere : {Machine{}, [] {
                                     Machine m = kHere;
                                     m.installation = "00000000000000bb";
                                     return m;
                                   }()}) {
    TimingRecord there = now;
    there.machine = elsewhere;
    CHECK(slowdowns(before, there, &judged).empty());
    CHECK(judged == 0);
  }
}

TEST_CASE("a record says which machine timed it, and two machines differ where they do",
          "[timing]") {
  const TimingRecord r{"a", "cpu", {timed("s", "ode", "1/60", 1.0)}, kHere};
  const Machine back = parse_timing_record(timing_json(r), "t").machine;
  CHECK(machine_differences(back, kHere).empty());
  CHECK(describe(back) ==
        "CPU x (family 6, model 207, stepping 2; L1d 48K, L2 2048K), 2 logical CPUs, Linux 6.1.0, "
        "installation 00000000000000aa");
  Machine other = kHere;
  other.caches = "L1d 32K";
  other.kernel = "6.2";
  CHECK(machine_differences(kHere, other) == std::vector<std::string>{"caches", "kernel"});
  // A record from before machines were written: every field unknown, so never the same machine.
  CHECK(machine_differences(Machine{}, kHere).size() == 6);
  CHECK(describe(Machine{}) == "not recorded");
  // This machine reads its own description, and is itself.
  const Machine here = this_machine();
  CHECK_FALSE(here.installation.empty());
  CHECK(here.logical_cpus >= 1);
  CHECK(machine_differences(here, this_machine()).empty());
  CHECK_THAT(parse_error("{\"commit\": \"a\", \"cpu\": \"c\", \"machine\": {\"cpu\": 1}, "
                         "\"cells\": []}"),
             Contains("out/timings.json") && Contains("machine.cpu"));
}

TEST_CASE("a timings.json from before samples were kept is named as such", "[timing]") {
  const std::string old =
      "{\"commit\": \"a\", \"cpu\": \"c\", \"cells\": [{\"scene\": \"s\", \"engine\": "
      "\"ode\", \"h\": \"1/60\", \"median_ms\": 1.0, \"q1_ms\": 1.0, \"q3_ms\": 1.0, "
      "\"min_ms\": 1.0, \"bare_median_ms\": 1.0, \"samples\": 8, \"replicas\": 1, "
      "\"repeats\": 1}]}";
  CHECK_THAT(parse_error(old), Contains("cells[0]: written by an older dropcheck, which kept no "
                                        "samples: write the report again"));
}
