#include "harness/report/verdict_files.hpp"

#include <algorithm>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "harness/io/xml_text.hpp"

namespace dropcheck {
namespace {

// How many records have each verdict (verdict_word).
struct Counts {
  int passed = 0, limits = 0, failed = 0, skipped = 0;
  void add(const CheckRecord& r) {
    const std::string v = verdict_word(r);
    (v == "pass" ? passed : v == "limit" ? limits : v == "fail" ? failed : skipped)++;
  }
  std::string attributes() const {
    return "tests=\"" + std::to_string(passed + limits + failed + skipped) + "\" failures=\"" +
           std::to_string(failed) + "\" errors=\"0\" skipped=\"" + std::to_string(skipped) + "\"";
  }
};

void write_case(std::ostream& out, const CheckRecord& r) {
  const CheckResult& c = r.result;
  out << "    <testcase classname=\"" << xml_escape(c.scene + "." + c.engine) << "\" name=\""
      << xml_escape(r.skipped ? std::string("run") : c.check) << "\"";
  if (r.skipped) {
    out << ">\n      <skipped message=\"" << xml_escape(r.skipped_because) << "\"/>\n"
        << "    </testcase>\n";
  } else if (!c.passed) {
    const std::string text = c.limit.empty() ? c.message : c.limit + "; " + c.message;
    out << ">\n      <failure message=\"" << xml_escape(text) << "\" type=\"FAIL\">"
        << xml_escape(text) << "</failure>\n    </testcase>\n";
  } else if (!c.limit.empty()) {
    out << ">\n      <system-out>LIMIT " << xml_escape(c.limit + "; " + c.message)
        << "</system-out>\n    </testcase>\n";
  } else {
    out << "/>\n";
  }
}

}  // namespace

std::vector<SceneOutcome> engine_outcomes(const std::vector<CheckRecord>& records,
                                          const std::string& engine) {
  std::vector<SceneOutcome> out;
  for (const CheckRecord& r : records) {
    if (r.result.engine != engine) continue;
    if (out.empty() || out.back().scene != r.result.scene)
      out.push_back({r.result.scene, "passed", 0, "", ""});
    SceneOutcome& o = out.back();
    if (r.skipped) {
      o.verdict = "skipped";
      o.detail = r.skipped_because;
      o.capability = capability_lifting(r.skipped_because);
      continue;
    }
    ++o.checks;
    if (!r.result.passed && o.verdict != "failed") {
      o.verdict = "failed";
      o.detail = r.result.check + ": " + r.result.message;
    }
  }
  return out;
}

std::string verdict_word(const CheckRecord& r) {
  if (r.skipped) return "skipped";
  if (!r.result.passed) return "fail";
  return r.result.limit.empty() ? "pass" : "limit";
}

void write_junit(std::ostream& out, const std::vector<CheckRecord>& records) {
  std::vector<std::string> scenes;  // in order of first appearance
  for (const CheckRecord& r : records)
    if (std::find(scenes.begin(), scenes.end(), r.result.scene) == scenes.end())
      scenes.push_back(r.result.scene);
  Counts all;
  for (const CheckRecord& r : records) all.add(r);
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<testsuites name=\"dropcheck check\" " << all.attributes() << ">\n";
  for (const std::string& scene : scenes) {
    Counts these;
    for (const CheckRecord& r : records)
      if (r.result.scene == scene) these.add(r);
    out << "  <testsuite name=\"" << xml_escape(scene) << "\" " << these.attributes() << ">\n";
    for (const CheckRecord& r : records)
      if (r.result.scene == scene) write_case(out, r);
    out << "  </testsuite>\n";
  }
  out << "</testsuites>\n";
}

void write_check_json(std::ostream& out, const std::vector<CheckRecord>& records) {
  using Json = nlohmann::ordered_json;
  Json results = Json::array();
  Counts n;
  for (const CheckRecord& r : records) {
    n.add(r);
    const std::string verdict = verdict_word(r);
    Json e;
    e["scene"] = r.result.scene;
    e["engine"] = r.result.engine;
    e["check"] = r.skipped ? std::string() : r.result.check;
    e["verdict"] = verdict;
    e["limit"] = r.result.limit;
    e["message"] = r.skipped ? r.skipped_because : r.result.message;
    results.push_back(std::move(e));
  }
  Json doc;
  doc["schema"] = "dropcheck-check/1";
  doc["passed"] = n.passed;
  doc["limits"] = n.limits;
  doc["failed"] = n.failed;
  doc["skipped"] = n.skipped;
  doc["results"] = std::move(results);
  // Invalid UTF-8 in a message (an engine's bytes) is replaced, never a throw.
  out << doc.dump(2, ' ', false, Json::error_handler_t::replace) << "\n";
}

}  // namespace dropcheck
