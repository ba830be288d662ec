// The baseline text format (harness/guard/baseline.hpp): writing, and parsing back to the bit.
#include "harness/guard/baseline_io.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/guard/baseline.hpp"
#include "harness/guard/baseline_parse.hpp"
#include "harness/io/bounded_read.hpp"
#include "harness/io/file_slug.hpp"
#include "harness/io/trajectory_io.hpp"

namespace dropcheck {
namespace {

std::string sweep_line(const SweepPoint& p) {
  return "sweep h=" + p.dt.text + " steps=" + std::to_string(p.steps) + " status=" + p.status +
         " analytic_max_dx=" + exact(p.analytic_max_dx) +
         " analytic_final_dx=" + exact(p.analytic_final_dx) + " law_max_dx=" + exact(p.law_max_dx) +
         " law_worst_body=" + p.law_worst_body +
         " law_first_over=" + std::to_string(p.law_first_over) + "\n";
}

std::string timing_line(const SweepPoint& p) {
  return "timing h=" + p.dt.text + " min_per_sim_s=" + exact(p.wall_min) +
         " median_per_sim_s=" + exact(p.wall_median) + " replicas=" + std::to_string(p.replicas) +
         "\n";
}

std::string samples_text(const Trajectory& t) {
  std::string out = "bodies";
  for (const std::string& name : t.body_names) {
    if (name.find_first_of(" \t\r\n") != std::string::npos)
      throw InputError(t.scene, 0, "body " + name,
                       "a baseline needs body names without whitespace");
    out += " " + name;
  }
  out += "\n# sample STEP BODY x y z vx vy vz\n";
  for (std::size_t s = 0; s < t.samples(); ++s) {
    for (std::size_t b = 0; b < t.bodies(); ++b) {
      const BodyState& st = t.at(s, b);
      out += "sample " + std::to_string(t.recorded[s]) + " " + t.body_names[b];
      for (int i = 0; i < 3; ++i) out.append(" ").append(exact(st.position[i]));
      for (int i = 0; i < 3; ++i) out.append(" ").append(exact(st.velocity[i]));
      out += "\n";
    }
  }
  return out;
}

}  // namespace

std::string baseline_to_text(const Baseline& b) {
  std::string out = kProvenancePrefix + b.provenance + "\n";
  for (const std::string& key : b.build_keys) out += "build_key " + key + "\n";
  out += "scene " + b.scene + "\nengine " + b.engine + "\nscalar " + to_string(b.scalar) +
         "\nlaw " + b.law + "\nanalytic " + b.analytic + "\n";
  if (!b.skipped.empty()) return out + "skipped " + b.skipped + "\n";
  out += "dt " + b.dt.text + " " + exact(b.dt.seconds) + "\nsteps " +
         std::to_string(b.samples.steps) + "\nrecord_every " + std::to_string(b.record_every) +
         "\nstatus " + b.status + "\nhash " + b.hash + "\n";
  if (!b.failed_tiers.empty()) out += "# FAILED " + b.failed_tiers + "\n";
  out +=
      "# sweep: |dx| against oracle 1 (analytic) and oracle 2 (own discrete law), worst body, m\n";
  for (const SweepPoint& p : b.sweep) out += sweep_line(p);
  for (const SweepPoint& p : b.sweep)
    if (!std::isnan(p.wall_min)) out += timing_line(p);
  if (!b.contact.empty())
    out += "# contact: what the run at dt shows of its slides, bounces, landings and stacks\n";
  for (const ContactFigure& f : b.contact) out += "contact " + f.name + " " + exact(f.value) + "\n";
  return out + samples_text(b.samples);
}

namespace {

[[noreturn]] void claim_error(const std::string& path, const std::string& field,
                              const std::string& stored, const std::string& now) {
  throw InputError(path, 0, field,
                   "the baseline says " + excerpt(stored) + ", but it was read for " +
                       excerpt(now) + "; it is not this run's baseline");
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : " ") + n;
  return out;
}

}  // namespace

void check_baseline_claims(const Baseline& stored, const Baseline& now, const std::string& path) {
  if (stored.scene != now.scene) claim_error(path, "scene", stored.scene, now.scene);
  if (stored.engine != now.engine) claim_error(path, "engine", stored.engine, now.engine);
  if (stored.scalar != now.scalar)
    claim_error(path, "scalar", to_string(stored.scalar), to_string(now.scalar));
  if (!stored.skipped.empty() || !now.skipped.empty()) return;  // no run: nothing more is claimed
  if (stored.dt.seconds != now.dt.seconds)
    claim_error(path, "dt", stored.dt.text + " (" + exact(stored.dt.seconds) + " s)",
                now.dt.text + " (" + exact(now.dt.seconds) + " s)");
  if (stored.samples.steps != now.samples.steps)
    claim_error(path, "steps", std::to_string(stored.samples.steps),
                std::to_string(now.samples.steps));
  if (stored.samples.body_names != now.samples.body_names)
    claim_error(path, "bodies", joined(stored.samples.body_names), joined(now.samples.body_names));
}

void check_baseline_file_name(const Baseline& b, const std::string& path) {
  const std::string expected = baseline_file_name(file_slug(b.scene), file_slug(b.engine));
  const std::string name = std::filesystem::path(path).filename().string();
  if (name != expected)
    throw InputError(path, 0, "scene/engine",
                     "the header names scene " + excerpt(b.scene) + " on engine " +
                         excerpt(b.engine) + ", whose baseline is " + excerpt(expected) +
                         ", not this file");
}

bool same_data(const std::string& a, const std::string& b) {
  auto strip = [](const std::string& text) {
    std::istringstream in(text);
    std::string line, out;
    while (std::getline(in, line))
      if (line.rfind(kProvenancePrefix, 0) != 0 && line.rfind("build_key ", 0) != 0)
        out += line + "\n";
    return out;
  };
  return strip(a) == strip(b);
}

// An entry exists at `path`, whatever it is (a dangling link too: it is refused, not "absent").
bool entry_exists(const std::string& path) {
  std::error_code ec;
  return std::filesystem::symlink_status(path, ec).type() != std::filesystem::file_type::not_found;
}

std::optional<Baseline> read_baseline_if_present(const std::string& path) {
  if (!entry_exists(path)) return std::nullopt;
  return read_baseline(path);
}

Baseline read_baseline(const std::string& path) {
  if (!entry_exists(path))
    throw InputError(path, 0, "", "no baseline file (run `dropcheck bless` to make it)");
  // A baseline folder is data from whoever made it: an entry that is a link, a device, a FIFO or a
  // folder is refused, never followed out of the folder.
  const std::string t =
      read_regular_file(path, kMaxBaselineBytes, "512 MiB, for a baseline", Links::refuse);
  const char* not_baseline =
      "is not a baseline (baselines are text written by `dropcheck bless`, whose first line is '# "
      "dropcheck baseline: ...')";
  // A control character (NUL, ESC, C1, ...) or invalid UTF-8 never occurs in a baseline, and a
  // file without the baseline's first line is someone else's: quote none of its bytes back.
  if (find_unsafe_byte(t) != std::string::npos) throw InputError(path, 0, "", not_baseline);
  if (t.rfind(kProvenancePrefix, 0) != 0) throw InputError(path, 1, "", not_baseline);
  return parse_baseline(t, path);
}

}  // namespace dropcheck
