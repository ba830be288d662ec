// Tests harness/measure/timing_record.cpp: timings.json reads back exactly, bad records are refused
// naming the file and key, and two records are compared cell by cell (the two-run figure of the
// report's "Timing reproducibility").
#include "harness/measure/timing_record.hpp"

#include <catch2/catch.hpp>

#include "harness/core/input_error.hpp"

using namespace dropcheck;
using Catch::Matchers::Contains;

namespace {

TimedCell timed(const std::string& scene, const std::string& engine, const std::string& h,
                double median_ms) {
  return {scene,           engine, h, median_ms, 0.9 * median_ms, 1.1 * median_ms, 0.8 * median_ms,
          0.5 * median_ms, 8,      4, 2};
}

std::string parse_error(const std::string& text) {
  try {
    parse_timing_record(text, "out/timings.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

TEST_CASE("a timings record reads back exactly what was written", "[timing]") {
  const TimingRecord r{"abc1234",
                       "CPU \"x\", 2 logical",
                       {timed("wind", "ours", "1/60", 0.1 / 3), timed("a,b", "ode", "0.01", 1e-300),
                        timed("wind", "bullet", "1/60", 12345.678901234567)}};
  const TimingRecord back = parse_timing_record(timing_json(r), "timings.json");
  CHECK(back.commit == r.commit);
  CHECK(back.cpu == r.cpu);
  REQUIRE(back.cells.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) {
    const TimedCell &a = r.cells[i], &b = back.cells[i];
    CHECK(std::tie(a.scene, a.engine, a.h, a.samples, a.replicas, a.repeats) ==
          std::tie(b.scene, b.engine, b.h, b.samples, b.replicas, b.repeats));
    CHECK(std::tie(a.median_ms, a.q1_ms, a.q3_ms, a.min_ms, a.bare_median_ms) ==
          std::tie(b.median_ms, b.q1_ms, b.q3_ms, b.min_ms, b.bare_median_ms));
  }
  CHECK(parse_timing_record(timing_json({"c", "cpu", {}}), "t").cells.empty());
}

TEST_CASE("a bad timings record is refused naming the file, the key and the problem", "[timing]") {
  const std::string cell =
      R"({"scene":"s","engine":"e","h":"1/60","median_ms":1,"q1_ms":1,"q3_ms":1,"min_ms":1,)"
      R"("bare_median_ms":1,"samples":8,"replicas":1,"repeats":1})";
  const auto with = [&](const std::string& c) {
    return R"({"commit":"c","cpu":"x","cells":[)" + cell + "," + c + "]}";
  };
  CHECK(parse_error(with(cell)) == "(accepted)");
  CHECK_THAT(parse_error("{\"commit\": "),
             Contains("out/timings.json") && Contains("not a timings"));
  CHECK_THAT(parse_error("[1, 2]"), Contains("expected a JSON object"));
  CHECK_THAT(parse_error(R"({"commit":"c","cpu":"x","cells":[{"median_ms":1e999}]})"),
             Contains("not a timings record") && Contains("number overflow"));
  CHECK_THAT(parse_error(R"({"commit":"c","cpu":"x"})"),
             Contains("cells: required key is missing"));
  CHECK_THAT(parse_error(R"({"commit":"c","cpu":"x","cells":{}})"),
             Contains("cells: expected an array, got object"));
  std::string missing = cell;
  missing.replace(missing.find(R"("median_ms":1,)"), 14, "");
  CHECK_THAT(parse_error(with(missing)), Contains("cells[1].median_ms: required key is missing"));
  std::string negative = cell;
  negative.replace(negative.find(R"("min_ms":1)"), 10, R"("min_ms":-1)");
  CHECK_THAT(parse_error(with(negative)),
             Contains("cells[1].min_ms: expected a finite number >= 0"));
  std::string text = cell;
  text.replace(text.find(R"("h":"1/60")"), 10, R"("h":60)");
  CHECK_THAT(parse_error(with(text)), Contains("cells[1].h: expected a string, got number"));
  std::string fraction = cell;
  fraction.replace(fraction.find(R"("samples":8)"), 11, R"("samples":8.5)");
  CHECK_THAT(parse_error(with(fraction)), Contains("cells[1].samples: expected a whole number"));
  CHECK_THAT(parse_error(with("7")), Contains("cells[1]: expected an object, got number"));
}

TEST_CASE("two timing records are compared on the cells both hold, once each", "[timing]") {
  const TimingRecord before{"a",
                            "cpu",
                            {timed("s", "ours", "1/60", 1.0), timed("s", "ode", "1/60", 2.0),
                             timed("s", "bullet", "1/60", 3.0), timed("s", "box2d", "1/60", 1.0),
                             timed("s", "box2d", "1/60", 1.0), timed("t", "ours", "1/60", 1.0)}};
  const TimingRecord now{"a",
                         "cpu",
                         {timed("s", "ours", "1/60", 1.09),    // +9 %: agrees
                          timed("s", "ode", "1/60", 1.6),      // 2 / 1.6 - 1 = 25 %
                          timed("s", "bullet", "1/60", 3.03),  // +1 %
                          timed("s", "box2d", "1/60", 1.0),    // twice in `before`: left out
                          timed("s", "ours", "1/120", 5.0)}};  // not in `before`: left out
  const TimingComparison c = compare_timings(before, now, 0.10, 2);
  CHECK(c.cells == 3);
  CHECK(c.agree == 2);
  CHECK(c.median_moved == Approx(0.09));
  REQUIRE(c.worst.size() == 2);
  CHECK(c.worst[0].now.engine == "ode");
  CHECK(c.worst[0].moved == Approx(0.25));
  CHECK(c.worst[1].now.engine == "ours");
  CHECK(compare_timings(now, now).agree == 5);
  CHECK(compare_timings(now, now).worst.size() == 5);  // keep = 5 by default
}
