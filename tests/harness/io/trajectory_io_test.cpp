// Tests harness/io/trajectory_io.cpp: CSV and JSON are well-formed and their numbers read back
// exactly.
#include "harness/io/trajectory_io.hpp"

#include <catch2/catch.hpp>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "harness/core/number_format.hpp"
#include "harness/io/json_text.hpp"

using Catch::Matchers::Contains;

namespace {

using dropcheck::Vec3;

// Values that need all 17 digits, the extremes, a subnormal and a negative zero.
const std::vector<double> kHard = {0.1,   1.0 / 3.0,         M_PI,    -2.5,
                                   1e300, DBL_MAX,           DBL_MIN, 4.9406564584124654e-324,
                                   -0.0,  6.5878983508563724};

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// One run of two bodies and three samples (steps 0, 5, 10) filled with kHard values.
dropcheck::Trajectory sample_run() {
  dropcheck::Trajectory t;
  t.engine = "ours-f64";
  t.scene = "io";
  t.h = 1.0 / 60.0;
  t.steps = 10;
  t.body_names = {"a", "b"};
  t.recorded = {0, 5, 10};
  std::size_t k = 0;
  for (int i = 0; i < 6; ++i) {
    dropcheck::BodyState s;
    for (int j = 0; j < 3; ++j) s.position[j] = kHard[k++ % kHard.size()];
    for (int j = 0; j < 3; ++j) s.velocity[j] = kHard[k++ % kHard.size()];
    t.states.push_back(s);
  }
  return t;
}

// Splits one CSV record by RFC 4180: fields in double quotes may hold commas and "" for a quote.
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      out.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// A strict JSON checker (RFC 8259 grammar); collects every number it reads, in order.
struct JsonChecker {
  explicit JsonChecker(const std::string& text) : s(text) {}
  const std::string& s;
  std::size_t i = 0;
  std::vector<double> numbers;

  void ws() {
    while (i < s.size() && std::strchr(" \t\r\n", s[i])) ++i;
  }
  bool lit(const char* w) {
    const std::size_t n = std::strlen(w);
    if (s.compare(i, n, w) != 0) return false;
    i += n;
    return true;
  }
  bool string() {
    if (!lit("\"")) return false;
    while (i < s.size() && s[i] != '"') {
      if (static_cast<unsigned char>(s[i]) < 0x20) return false;
      if (s[i] == '\\') {
        ++i;
        if (i >= s.size() || !std::strchr("\"\\/bfnrtu", s[i])) return false;
      }
      ++i;
    }
    return lit("\"");
  }
  bool number() {
    const std::size_t start = i;
    if (i < s.size() && s[i] == '-') ++i;
    if (i >= s.size() || !std::isdigit(static_cast<unsigned char>(s[i]))) return false;
    if (s[i] == '0' && i + 1 < s.size() && std::isdigit(static_cast<unsigned char>(s[i + 1])))
      return false;
    while (i < s.size() && std::strchr("0123456789.eE+-", s[i])) ++i;
    const std::string text = s.substr(start, i - start);
    char* end = nullptr;
    numbers.push_back(std::strtod(text.c_str(), &end));
    return *end == '\0';
  }
  // The items of an object or array after its opening bracket: none, or `item`s separated by
  // commas, then `close`.
  template <typename Item>
  bool items(const char* close, Item item) {
    ws();
    if (lit(close)) return true;
    for (;;) {
      if (!item()) return false;
      ws();
      if (lit(close)) return true;
      if (!lit(",")) return false;
    }
  }
  bool value() {
    ws();
    bool ok = false;
    if (i >= s.size()) return false;
    if (s[i] == '{') {
      ++i;
      ok = items("}", [this] {  // "key": value
        ws();
        if (!string()) return false;
        ws();
        return lit(":") && value();
      });
    } else if (s[i] == '[') {
      ++i;
      ok = items("]", [this] { return value(); });
    } else if (s[i] == '"') {
      ok = string();
    } else {
      ok = lit("true") || lit("false") || lit("null") || number();
    }
    ws();
    return ok;
  }
  bool document() { return value() && i == s.size(); }
};

}  // namespace

TEST_CASE("exact() prints doubles that read back bit for bit", "[trajectory_io]") {
  for (double v : kHard) {
    const std::string text = dropcheck::exact(v);
    INFO(text);
    CHECK(same_bits(std::strtod(text.c_str(), nullptr), v));
  }
  CHECK(dropcheck::exact(0.1) == "0.10000000000000001");  // %.17g, not the shortest form
}

TEST_CASE(
    "the CSV has the contract's header, one row per body per sample and numbers that read back "
    "exactly",
    "[trajectory_io]") {
  const dropcheck::Trajectory t = sample_run();
  const std::vector<std::string> lines = lines_of(dropcheck::trajectories_to_csv({&t, 1}));
  REQUIRE(lines.size() == 1 + 3 * 2);
  CHECK(lines[0] == "engine,dt,step,t,body,x,y,z,vx,vy,vz");
  for (std::size_t r = 1; r < lines.size(); ++r) {
    const std::vector<std::string> f = csv_fields(lines[r]);
    REQUIRE(f.size() == 11);
    const std::size_t sample = (r - 1) / 2, body = (r - 1) % 2;
    CHECK(f[0] == "ours-f64");
    CHECK(same_bits(std::strtod(f[1].c_str(), nullptr), t.h));
    CHECK(f[2] == std::to_string(t.recorded[sample]));
    CHECK(same_bits(std::strtod(f[3].c_str(), nullptr), t.time(sample)));
    CHECK(f[4] == t.body_names[body]);
    const dropcheck::BodyState& s = t.at(sample, body);
    for (int j = 0; j < 3; ++j) {
      CHECK(same_bits(std::strtod(f[5 + j].c_str(), nullptr), s.position[j]));
      CHECK(same_bits(std::strtod(f[8 + j].c_str(), nullptr), s.velocity[j]));
    }
  }
}

TEST_CASE("a body name with a comma or a quote stays one CSV field", "[trajectory_io]") {
  dropcheck::Trajectory t = sample_run();
  t.body_names = {"left, top", "say \"hi\""};
  const std::vector<std::string> lines = lines_of(dropcheck::trajectories_to_csv({&t, 1}));
  REQUIRE(lines.size() == 7);
  const std::vector<std::string> a = csv_fields(lines[1]), b = csv_fields(lines[2]);
  CHECK(a.size() == 11);
  CHECK(b.size() == 11);
  CHECK(a[4] == "left, top");
  CHECK(b[4] == "say \"hi\"");
  CHECK(lines[1].rfind("ours-f64,", 0) == 0);  // plain fields stay unquoted
}

TEST_CASE("the JSON is well-formed, keeps every sample and its numbers read back exactly",
          "[trajectory_io]") {
  const dropcheck::Trajectory t = sample_run();
  const std::vector<dropcheck::Trajectory> runs{t, t};
  const std::string json = dropcheck::trajectories_to_json(runs);
  JsonChecker j{json};
  REQUIRE(j.document());
  CHECK_THAT(json, Contains("\"engine\":\"ours-f64\"") && Contains("\"status\":\"ok\"") &&
                       Contains("\"name\":\"b\""));
  // Per run: dt, steps, failed_step, clamped_steps, then per body and sample: step, x, y, z, vx,
  // vy, vz.
  REQUIRE(j.numbers.size() == 2 * (4 + 2 * 3 * 7));
  for (std::size_t run = 0; run < 2; ++run) {
    const double* n = j.numbers.data() + run * (4 + 2 * 3 * 7);
    CHECK(same_bits(n[0], t.h));
    for (std::size_t b = 0; b < 2; ++b) {
      for (std::size_t s = 0; s < 3; ++s) {
        const double* row = n + 4 + (b * 3 + s) * 7;
        CHECK(row[0] == double(t.recorded[s]));
        for (int k = 0; k < 3; ++k) {
          CHECK(same_bits(row[1 + k], t.at(s, b).position[k]));
          CHECK(same_bits(row[4 + k], t.at(s, b).velocity[k]));
        }
      }
    }
  }
}

TEST_CASE("NaN and Inf are written as null in JSON, and names are escaped", "[trajectory_io]") {
  dropcheck::Trajectory t = sample_run();
  t.states[0].position.x() = std::numeric_limits<double>::quiet_NaN();
  t.states[0].velocity.y() = -std::numeric_limits<double>::infinity();
  t.body_names[0] = "quote\" back\\ tab\t";
  t.status = dropcheck::RunStatus::non_finite;
  t.failure = "line1\nline2";
  const std::string json = dropcheck::trajectories_to_json({&t, 1});
  JsonChecker j{json};
  CHECK(j.document());
  CHECK_THAT(json, Contains("[0,[null,") && Contains(",[-2.5,null,"));
  CHECK_THAT(json, Contains("\"quote\\\" back\\\\ tab\\t\"") && Contains("\"line1\\nline2\""));
  CHECK_THAT(json, !Contains("nan") && !Contains("inf"));
}

TEST_CASE("no runs still give a header-only CSV and a well-formed JSON", "[trajectory_io]") {
  CHECK(dropcheck::trajectories_to_csv({}) == "engine,dt,step,t,body,x,y,z,vx,vy,vz\n");
  const std::string json = dropcheck::trajectories_to_json({});
  JsonChecker j{json};
  CHECK(j.document());
}

TEST_CASE("the streamed JSON has the bytes nlohmann writes for the whole document",
          "[trajectory_io]") {
  dropcheck::Trajectory hard = sample_run(), empty = sample_run(), none;
  hard.body_names[1] = "bad \xff byte, \"quoted\"";  // not UTF-8: written as U+FFFD
  hard.states[3].velocity.z() = std::numeric_limits<double>::quiet_NaN();
  empty.recorded.clear();  // bodies without samples
  empty.states.clear();
  none.engine = "none";  // no bodies at all
  const std::vector<dropcheck::Trajectory> runs{hard, empty, none};
  std::ostringstream streamed;
  dropcheck::write_trajectories_json(streamed, runs);
  // Read back and written again whole, each run on its own line, as the old writer did.
  const auto doc = dropcheck::parse_json<nlohmann::ordered_json>(streamed.str());
  std::string whole = "{\"runs\":[";
  for (std::size_t r = 0; r < doc["runs"].size(); ++r)
    whole += (r ? ",\n" : "\n") + dropcheck::json_text(doc["runs"][r]);
  whole += "\n]}\n";
  CHECK(streamed.str() == whole);
  CHECK(doc["runs"][0]["bodies"][1]["name"] == "bad \xef\xbf\xbd byte, \"quoted\"");
  CHECK(doc["runs"][1]["bodies"][0]["samples"].empty());
  CHECK(doc["runs"][2]["bodies"].empty());
}
