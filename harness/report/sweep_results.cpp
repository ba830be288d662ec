#include "harness/report/sweep_results.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "harness/core/input_error.hpp"
#include "harness/io/bounded_read.hpp"
#include "harness/io/json_text.hpp"

namespace dropcheck {
namespace {

using Json = nlohmann::ordered_json;

std::optional<double> result_number(const Json& j) {
  if (j.is_number()) return j.get<double>();
  if (j.is_string()) {
    const std::string s = j.get<std::string>();
    if (s == "inf") return INFINITY;
    if (s == "-inf") return -INFINITY;
    if (s == "nan") return NAN;
  }
  return std::nullopt;
}

SweepCell cell_of(const Json& j) {
  SweepCell c;
  c.key = j.at("key").get<std::string>();
  c.scene = j.at("scene").get<std::string>();
  c.status = j.at("status").get<std::string>();
  c.reason = j.value("reason", "");
  c.engine = j.contains("engine")
                 ? j["engine"].at("name").get<std::string>()
                 : c.key.substr(c.key.find('|') + 1,
                                c.key.find('|', c.key.find('|') + 1) - c.key.find('|') - 1);
  for (const auto& [name, value] : j.at("axes").items())
    c.axes.emplace_back(name, value.get<std::string>());
  if (j.contains("error") && j["error"].contains("closed_form") &&
      j["error"]["closed_form"].is_object())
    c.error = result_number(j["error"]["closed_form"].at("max_dx"));
  if (j.contains("stability")) {
    c.theory_max_h = result_number(j["stability"].at("theory_max_h"));
    c.law_unstable = j["stability"].value("law_unstable", "");
  }
  if (j.contains("timing")) {
    c.ns_per_body_step = result_number(j["timing"].at("ns_per_body_step"));
    c.cpu = j["timing"].value("cpu", "");
  }
  return c;
}

// Line `n` of the file `name` (escaped) added to `out` as a record; an empty line is skipped.
void add_record(std::vector<SweepCell>& out, const std::string& line, const std::string& name,
                long long n) {
  if (line.empty()) return;
  try {
    const Json j = parse_json<Json>(line);
    if (j.value("format", "") != "dropcheck-record/1") throw std::invalid_argument("format");
    out.push_back(cell_of(j));
  } catch (const std::exception&) {
    throw InputError(name + ":" + std::to_string(n), 0, "",
                     "not a dropcheck-record/1 record: " + excerpt(line));
  }
}

void require_records(const std::vector<SweepCell>& out, const std::string& name) {
  if (out.empty()) throw InputError(escape_controls(name), 0, "", "holds no record");
}

}  // namespace

std::vector<SweepCell> read_sweep_results(const std::string& path) {
  LineReader in(path, kMaxResultBytes, kMaxResultLine, "a result file");
  std::vector<SweepCell> out;
  for (std::string line; in.next(line);) add_record(out, line, in.name(), in.line_number());
  require_records(out, path);
  return out;
}

std::vector<SweepCell> parse_sweep_results(std::string_view text, const std::string& name) {
  const std::string escaped = escape_controls(name);
  std::vector<SweepCell> out;
  long long n = 0;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    std::string line(text.substr(at, end - at));
    at = end + 1;
    ++n;
    if (line.size() > kMaxResultLine)
      throw InputError(
          escaped, static_cast<int>(n), "",
          "a line longer than " + std::to_string(kMaxResultLine) + " bytes: not a result file");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    add_record(out, line, escaped, n);
  }
  require_records(out, name);
  return out;
}

}  // namespace dropcheck
