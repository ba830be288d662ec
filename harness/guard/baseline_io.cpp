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
      for (int i = 0; i < 3; ++i) out += " " + exact(st.position[i]);
      for (int i = 0; i < 3; ++i) out += " " + exact(st.velocity[i]);
      out += "\n";
    }
  }
  return out;
}

}  // namespace

std::string baseline_to_text(const Baseline& b) {
  std::string out = kProvenancePrefix + b.provenance + "\n";
  out += "build_key " + b.build_key + "\nscene " + b.scene + "\nengine " + b.engine + "\nscalar " +
         to_string(b.scalar) + "\nlaw " + b.law + "\nanalytic " + b.analytic + "\n";
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
  return out + samples_text(b.samples);
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

// Largest baseline file read. A baseline stores every 10th step: the largest run (kMaxSteps steps)
// of one body is 2e6 sample lines of about 150 bytes, 300 MB; the shipped ones are under 30 KiB.
constexpr std::int64_t kMaxBaselineBytes = std::int64_t{512} << 20;

std::optional<Baseline> read_baseline_if_present(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  return read_baseline(path);
}

Baseline read_baseline(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec))
    throw InputError(path, 0, "", "no baseline file (run `dropcheck bless` to make it)");
  const std::string t = read_regular_file(path, kMaxBaselineBytes, "512 MiB, for a baseline");
  // A control byte (NUL, ESC, ...) never occurs in a baseline: quote no raw bytes back.
  if (std::any_of(t.begin(), t.end(), [](char c) {
        return (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\r' && c != '\t') ||
               c == 0x7f;
      }))
    throw InputError(
        path, 0, "",
        "is a binary file, not a baseline (baselines are text written by `dropcheck bless`)");
  return parse_baseline(t, path);
}

}  // namespace dropcheck
