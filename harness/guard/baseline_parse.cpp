// Parsing the baseline text format (harness/guard/baseline.hpp) back into a Baseline, to the bit:
// every number was printed with %.17g, which strtod reads back exactly.
#include "harness/guard/baseline_parse.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <vector>

#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/timestep.hpp"
#include "harness/guard/baseline.hpp"

namespace dropcheck {
namespace {

struct Parser {
  std::string path;
  int line = 0;
  Baseline b;
  std::size_t next_body = 0;  // index of the body the next `sample` line must name

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throw InputError(path, line, key, problem);
  }

  double number(const std::string& text, const std::string& key) const {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0') fail(key, "not a number: " + excerpt(text));
    return v;
  }

  // A whole number that fits in 64 bits (strtoll saturates: ERANGE is refused).
  std::int64_t integer(const std::string& text, const std::string& key) const {
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE)
      fail(key, "not an integer: " + excerpt(text));
    return v;
  }

  // "k1=v1 k2=v2 ..." with exactly the keys in `expected`.
  std::map<std::string, std::string> fields(const std::string& rest, const std::string& key,
                                            const std::vector<std::string>& expected) const {
    std::map<std::string, std::string> out;
    std::istringstream in(rest);
    std::string word;
    while (in >> word) {
      const std::size_t eq = word.find('=');
      if (eq == std::string::npos) fail(key, "expected name=value, got " + excerpt(word));
      out[word.substr(0, eq)] = word.substr(eq + 1);
    }
    for (const std::string& e : expected)
      if (!out.count(e)) fail(key, "missing " + e + "=");
    if (out.size() != expected.size()) fail(key, "unexpected fields in " + excerpt(rest));
    return out;
  }

  void sweep(const std::string& rest) {
    auto f = fields(rest, "sweep",
                    {"h", "steps", "status", "analytic_max_dx", "analytic_final_dx", "law_max_dx",
                     "law_worst_body", "law_first_over"});
    SweepPoint p;
    std::string why;
    const std::optional<Timestep> dt = parse_timestep(f["h"], why);
    if (!dt) fail("sweep h", why);
    p.dt = *dt;
    p.steps = integer(f["steps"], "sweep steps");
    p.status = f["status"];
    p.analytic_max_dx = number(f["analytic_max_dx"], "sweep analytic_max_dx");
    p.analytic_final_dx = number(f["analytic_final_dx"], "sweep analytic_final_dx");
    p.law_max_dx = number(f["law_max_dx"], "sweep law_max_dx");
    p.law_worst_body = f["law_worst_body"];
    p.law_first_over = integer(f["law_first_over"], "sweep law_first_over");
    b.sweep.push_back(p);
  }

  void timing(const std::string& rest) {
    auto f = fields(rest, "timing", {"h", "min_per_sim_s", "median_per_sim_s", "replicas"});
    for (SweepPoint& p : b.sweep) {
      if (p.dt.text != f["h"]) continue;
      p.wall_min = number(f["min_per_sim_s"], "timing min_per_sim_s");
      p.wall_median = number(f["median_per_sim_s"], "timing median_per_sim_s");
      p.replicas = static_cast<int>(integer(f["replicas"], "timing replicas"));
      return;
    }
    fail("timing", "no sweep line for h=" + f["h"]);
  }

  void dt(const std::string& rest) {
    std::istringstream in(rest);
    std::string text, seconds, extra;
    if (!(in >> text >> seconds) || (in >> extra)) fail("dt", "expected 'dt TEXT SECONDS'");
    // The text is what the step was written as ("1/60"), the number what it was: they must agree.
    std::string why;
    const std::optional<Timestep> step = parse_timestep(text, why);
    if (!step) fail("dt", excerpt(text) + ": " + why);
    const double s = number(seconds, "dt");
    if (s != step->seconds)
      fail("dt", excerpt(text) + " is " + exact(step->seconds) + " s, but the file says " +
                     excerpt(seconds));
    b.dt = *step;
  }

  std::int64_t positive(const std::string& text, const std::string& key) const {
    const std::int64_t v = integer(text, key);
    if (v < 1) fail(key, "must be at least 1, got " + excerpt(text));
    return v;
  }

  // "contact BODY.FIGURE VALUE" (contact_figures): BODY.FIGURE once each, at most
  // kMaxContactFigures of them; a *_step value an integer >= -1, any other finite.
  void contact(const std::string& rest) {
    std::istringstream in(rest);
    std::string name, value, extra;
    if (!(in >> name >> value) || (in >> extra)) fail("contact", "expected 'contact NAME VALUE'");
    if (b.contact.size() >= kMaxContactFigures)
      fail("contact", "more than " + std::to_string(kMaxContactFigures) + " figures");
    for (const ContactFigure& f : b.contact)
      if (f.name == name) fail("contact", "a second " + excerpt(name));
    const std::string key = "contact " + excerpt(name);
    double v = 0.0;
    if (name.ends_with("_step")) {
      const std::int64_t step = integer(value, key);
      if (step < -1) fail(key, "a step of -1 (never) or more, got " + excerpt(value));
      v = static_cast<double>(step);
    } else {
      v = number(value, key);
      if (!std::isfinite(v)) fail(key, "a finite figure, got " + excerpt(value));
    }
    b.contact.push_back({name, v});
  }

  void bodies(const std::string& rest) {
    // A second list would change the body count of samples already read (found by fuzzing:
    // baseline_to_text then read past the stored states).
    if (!b.samples.body_names.empty()) fail("bodies", "a second 'bodies' line");
    std::istringstream in(rest);
    std::string name;
    while (in >> name) b.samples.body_names.push_back(name);
    if (b.samples.body_names.empty()) fail("bodies", "no body names");
  }

  void sample(const std::string& rest) {
    std::istringstream in(rest);
    std::vector<std::string> w;
    for (std::string word; in >> word;) w.push_back(word);
    if (w.size() != 8) fail("sample", "expected STEP BODY x y z vx vy vz");
    Trajectory& t = b.samples;
    if (t.body_names.empty()) fail("sample", "before the 'bodies' line");
    const std::int64_t step = integer(w[0], "sample step");
    if (next_body == 0) t.recorded.push_back(step);
    if (step != t.recorded.back())
      fail("sample", "step " + w[0] + " before every body of step " +
                         std::to_string(t.recorded.back()) + " was listed");
    if (w[1] != t.body_names[next_body])
      fail("sample",
           "expected body " + excerpt(t.body_names[next_body]) + ", got " + excerpt(w[1]));
    BodyState s;
    const std::string key = "sample " + excerpt(w[1]);
    for (int i = 0; i < 3; ++i) s.position[i] = number(w[2 + i], key);
    for (int i = 0; i < 3; ++i) s.velocity[i] = number(w[5 + i], key);
    t.states.push_back(s);
    next_body = (next_body + 1) % t.body_names.size();
  }

  void build_key(const std::string& rest) {
    if (b.build_keys.size() >= kMaxBuildKeys)
      fail("build_key", "more than " + std::to_string(kMaxBuildKeys) + " build keys");
    b.build_keys.push_back(rest);
  }

  Scalar scalar(const std::string& rest) const {
    if (rest == "f32") return Scalar::f32;
    if (rest != "f64") fail("scalar", "expected f32 or f64, got " + excerpt(rest));
    return Scalar::f64;
  }

  void record(const std::string& key, const std::string& rest) {
    if (key == "build_key")
      build_key(rest);
    else if (key == "scene")
      b.scene = rest;
    else if (key == "engine")
      b.engine = rest;
    else if (key == "scalar")
      b.scalar = scalar(rest);
    else if (key == "law")
      b.law = rest;
    else if (key == "analytic")
      b.analytic = rest;
    else if (key == "skipped")
      b.skipped = rest;
    else if (key == "dt")
      dt(rest);
    else if (key == "steps")
      b.samples.steps = positive(rest, key);
    else if (key == "record_every")
      b.record_every = positive(rest, key);
    else if (key == "status")
      b.status = rest;
    else if (key == "hash")
      b.hash = rest;
    else if (key == "sweep")
      sweep(rest);
    else if (key == "timing")
      timing(rest);
    else if (key == "contact")
      contact(rest);
    else if (key == "bodies")
      bodies(rest);
    else if (key == "sample")
      sample(rest);
    else
      fail("", "unknown record " + excerpt(key));
  }

  // The recorded steps are the ones the header says were kept: 0, record_every, 2*record_every,
  // ... and the last step run, which is `steps` when the run ended ok (earlier when it failed).
  void check_recorded_steps() {
    const std::vector<std::int64_t>& r = b.samples.recorded;
    const std::int64_t every = b.record_every, last = r.back();
    if (r.front() != 0)
      fail("sample", "the first sample is step " + std::to_string(r.front()) + ", not 0");
    for (std::size_t i = 0; i + 1 < r.size(); ++i)
      if (r[i] != static_cast<std::int64_t>(i) * every)
        fail("sample", "step " + std::to_string(r[i]) + " where record_every " +
                           std::to_string(every) + " keeps step " +
                           std::to_string(static_cast<std::int64_t>(i) * every));
    if (r.size() > 1 && last <= r[r.size() - 2])
      fail("sample", "the last step " + std::to_string(last) + " does not follow step " +
                         std::to_string(r[r.size() - 2]));
    if (r.size() > 1 && last - r[r.size() - 2] > every)
      fail("sample", "steps between " + std::to_string(r[r.size() - 2]) + " and " +
                         std::to_string(last) + " are missing (record_every " +
                         std::to_string(every) + ")");
    if (last > b.samples.steps || (b.status == "ok" && last != b.samples.steps))
      fail("steps", "the header says " + std::to_string(b.samples.steps) +
                        " steps, but the samples end at step " + std::to_string(last) +
                        (b.status == "ok" ? " of a run that ended ok" : ""));
  }

  void finish() {
    line = 0;
    if (b.scene.empty() || b.engine.empty()) fail("", "no 'scene' or 'engine' line");
    if (!b.skipped.empty()) return;
    if (b.hash.empty() || b.samples.recorded.empty()) fail("", "no 'hash' or no samples");
    if (next_body != 0) fail("sample", "the last step does not list every body");
    if (b.samples.states.size() != b.samples.recorded.size() * b.samples.body_names.size())
      fail("sample", "the samples do not list every body at every step");
    if (b.dt.text.empty()) fail("dt", "no 'dt' line");
    check_recorded_steps();
    b.samples.engine = b.engine;
    b.samples.scene = b.scene;
    b.samples.h = b.dt.seconds;
  }
};

}  // namespace

Baseline parse_baseline(const std::string& text, const std::string& path) {
  Parser p;
  p.path = path;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    ++p.line;
    if (line.rfind(kProvenancePrefix, 0) == 0) {
      p.b.provenance = line.substr(std::string(kProvenancePrefix).size());
      continue;
    }
    if (line.empty() || line[0] == '#') continue;
    const std::size_t space = line.find(' ');
    p.record(line.substr(0, space), space == std::string::npos ? "" : line.substr(space + 1));
  }
  p.finish();
  return p.b;
}

}  // namespace dropcheck
