#include "harness/report/verdict_files.hpp"

#include <algorithm>
#include <cstdint>
#include <nlohmann/json.hpp>

namespace dropcheck {
namespace {

// The length of the valid UTF-8 sequence at s[i] that XML 1.0 may carry (not U+FFFE, U+FFFF or a
// surrogate), or 0.
std::size_t xml_char_length(const std::string& s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(i);
  const std::size_t n = b < 0x80           ? 1
                        : (b >> 5) == 0x6  ? 2
                        : (b >> 4) == 0xE  ? 3
                        : (b >> 3) == 0x1E ? 4
                                           : 0;
  if (n == 0 || i + n > s.size()) return 0;
  std::uint32_t code = n == 1 ? b : b & (0x7F >> n);
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) >> 6) != 0x2) return 0;
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  const std::uint32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
  if (code < least[n] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF) || code == 0xFFFE ||
      code == 0xFFFF)
    return 0;
  return n;
}

// XML 1.0 text, for an element or an attribute: the five markup characters as entities, tab and
// newline as character references (an attribute would turn them into spaces); a control character
// XML 1.0 cannot carry, or a byte that is not valid UTF-8, as U+FFFD.
std::string xml_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const char c = s[i];
    const std::size_t n = xml_char_length(s, i);
    if (n == 0 ||
        (n == 1 && static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r')) {
      out += "\xEF\xBF\xBD";
      i += 1;
      continue;
    }
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      case '\t':
        out += "&#9;";
        break;
      case '\n':
        out += "&#10;";
        break;
      case '\r':
        out += "&#13;";
        break;
      default:
        out.append(s, i, n);
    }
    i += n;
  }
  return out;
}

struct Counts {
  int tests = 0, failures = 0, skipped = 0;
  void add(const CheckRecord& r) {
    ++tests;
    failures += !r.skipped && !r.result.passed;
    skipped += r.skipped;
  }
  std::string attributes() const {
    return "tests=\"" + std::to_string(tests) + "\" failures=\"" + std::to_string(failures) +
           "\" errors=\"0\" skipped=\"" + std::to_string(skipped) + "\"";
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
  int passed = 0, limits = 0, failed = 0, skipped = 0;
  for (const CheckRecord& r : records) {
    const std::string verdict = verdict_word(r);
    passed += verdict == "pass";
    limits += verdict == "limit";
    failed += verdict == "fail";
    skipped += verdict == "skipped";
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
  doc["passed"] = passed;
  doc["limits"] = limits;
  doc["failed"] = failed;
  doc["skipped"] = skipped;
  doc["results"] = std::move(results);
  // Invalid UTF-8 in a message (an engine's bytes) is replaced, never a throw.
  out << doc.dump(2, ' ', false, Json::error_handler_t::replace) << "\n";
}

}  // namespace dropcheck
