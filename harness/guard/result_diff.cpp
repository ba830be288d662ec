#include "harness/guard/result_diff.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/guard/baseline_io.hpp"
#include "harness/guard/regression.hpp"

namespace dropcheck {
namespace {

// Readable numbers: 3 significant digits for errors, 9 for coordinates ("-" for NaN).
std::string digits(double v, int n) {
  return std::isnan(v) ? "-" : sig(v, n);
}
std::string g3_or_dash(double v) {
  return digits(v, 3);
}

const SweepPoint* find_h(const Baseline& b, const std::string& h) {
  for (const SweepPoint& p : b.sweep)
    if (p.dt.text == h) return &p;
  return nullptr;
}

bool sweep_moved(const Baseline& before, const Baseline& after, double tol) {
  if (before.sweep.size() != after.sweep.size()) return true;
  for (const SweepPoint& a : after.sweep) {
    const SweepPoint* b = find_h(before, a.dt.text);
    if (!b || b->status != a.status) return true;
    if (std::abs(b->analytic_max_dx - a.analytic_max_dx) > tol) return true;
  }
  return false;
}

// "| max |dx| | first step over tolerance |" cells for a pair that ran in both sets.
std::string movement_cells(const Baseline& before, const Baseline& after) {
  const double tol = regression_tolerance(after.scalar);
  const SampleDiff d = diff_samples(before.samples, after.samples, tol);
  if (!d.incomparable.empty()) return "- | " + d.incomparable;
  std::string cells = d.max_dx == 0.0
                          ? "0 m | "
                          : sig(d.max_dx, 3) + " m (step " + std::to_string(d.max_step) + ") | ";
  if (d.first_step < 0) return cells + "- (tolerance " + g3_or_dash(tol) + " m)";
  // sig() prints a NaN as "nan": here it is a stored value, not a missing one.
  return cells + "step " + std::to_string(d.first_step) + ", " + d.first_body + "." + d.component +
         ": " + sig(d.before, 9) + " -> " + sig(d.after, 9) + " (" + sig(d.first_delta, 3) + ")";
}

std::string summary_row(const Baseline* before, const Baseline* after) {
  const Baseline& any = after ? *after : *before;
  const Movement m = classify(before, after);
  std::string row = "| " + any.scene + " | " + any.engine + " | " + to_string(m) + " | ";
  if (m == Movement::skipped)
    return row + "- | " + (after && !after->skipped.empty() ? after->skipped : before->skipped) +
           " | - |\n";
  if (!before || !after || !before->skipped.empty() || !after->skipped.empty())
    return row + "- | - | - |\n";
  return row + movement_cells(*before, *after) + " | " + before->hash + " -> " + after->hash +
         " |\n";
}

// Rows of the error-against-run-time table for one pair: every h whose numbers differ.
std::string curve_rows(const Baseline& before, const Baseline& after, bool timing, int& omitted) {
  std::string rows;
  for (const SweepPoint& a : after.sweep) {
    const SweepPoint* b = find_h(before, a.dt.text);
    if (!b) continue;
    const bool same_error = b->analytic_max_dx == a.analytic_max_dx ||
                            (std::isnan(b->analytic_max_dx) && std::isnan(a.analytic_max_dx));
    if (same_error && !timing) {
      ++omitted;
      continue;
    }
    rows += "| " + after.scene + " | " + after.engine + " | " + a.dt.text + " | " +
            g3_or_dash(b->analytic_max_dx) + " | " + g3_or_dash(a.analytic_max_dx) + " | " +
            g3_or_dash(a.analytic_max_dx / b->analytic_max_dx);
    if (timing)
      rows += " | " + g3_or_dash(b->wall_min * 1e3) + " | " + g3_or_dash(a.wall_min * 1e3);
    rows += " |\n";
  }
  return rows;
}

bool has_timing(const ResultSet& s) {
  for (const auto& [file, b] : s.runs)
    for (const SweepPoint& p : b.sweep)
      if (!std::isnan(p.wall_min)) return true;
  return false;
}

std::string curves_section(const ResultSet& before, const ResultSet& after) {
  const bool timing = has_timing(before) || has_timing(after);
  std::string out =
      "\n## Error against run time\n\nPer h of each scene's sweep: max |dx| against the "
      "analytic solution (m)";
  out += timing ? " and wall time per simulated second (ms, minimum of repeats).\n\n"
                : ". The result sets carry no timing (`dropcheck bless --timing` adds it).\n\n";
  out += "| scene | engine | h | error before | error after | after/before |";
  out += timing ? " wall before | wall after |\n|---|---|---|---:|---:|---:|---:|---:|\n"
                : "\n|---|---|---|---:|---:|---:|\n";
  int omitted = 0;
  std::string rows;
  for (const auto& [file, a] : after.runs) {
    const auto b = before.runs.find(file);
    if (b == before.runs.end() || !a.skipped.empty() || !b->second.skipped.empty()) continue;
    rows += curve_rows(b->second, a, timing, omitted);
  }
  if (rows.empty())
    return "\n## Error against run time\n\nNo curve moved (" + std::to_string(omitted) +
           " points identical).\n";
  out += rows;
  if (omitted) out += "\n" + std::to_string(omitted) + " points with identical errors omitted.\n";
  return out;
}

// A contact figure as its name reads: a step as an integer ("never" for -1; a stop step -1 "slides
// on" and 0 "never moves"), a distance or height in m to 7 digits; "-" when the set has no such
// figure.
std::string figure_text(const std::string& name, const ContactFigure* f) {
  if (!f) return "-";
  if (name.ends_with(".stop_step") && f->value <= 0.0)
    return f->value < 0.0 ? "slides on" : "never moves";
  if (name.ends_with("_step"))
    return f->value < 0.0 ? "never" : std::to_string(static_cast<long long>(f->value));
  return digits(f->value, 7) + " m";
}

const ContactFigure* find_figure(const Baseline& b, const std::string& name) {
  for (const ContactFigure& f : b.contact)
    if (f.name == name) return &f;
  return nullptr;
}

// Rows for each contact figure of a pair that differs between the two sets.
std::string contact_rows(const Baseline& before, const Baseline& after, int& same) {
  std::vector<std::string> names;
  for (const Baseline* b : {&before, &after})
    for (const ContactFigure& f : b->contact)
      if (std::find(names.begin(), names.end(), f.name) == names.end()) names.push_back(f.name);
  std::string rows;
  for (const std::string& name : names) {
    const ContactFigure *b = find_figure(before, name), *a = find_figure(after, name);
    if (a && b && a->value == b->value) {
      ++same;
      continue;
    }
    rows += "| " + after.scene + " | " + after.engine + " | " + name + " | " +
            figure_text(name, b) + " -> " + figure_text(name, a) + " |\n";
  }
  return rows;
}

// What moved in contact terms: each slide's stop step and distance, each bounce's first contact
// and apexes, for every pair both sets ran.
std::string contact_section(const ResultSet& before, const ResultSet& after) {
  int same = 0;
  std::string rows;
  for (const auto& [file, a] : after.runs) {
    const auto b = before.runs.find(file);
    if (b == before.runs.end() || !a.skipped.empty() || !b->second.skipped.empty()) continue;
    rows += contact_rows(b->second, a, same);
  }
  const std::string identical =
      std::to_string(same) + (same == 1 ? " figure identical" : " figures identical");
  if (rows.empty())
    return "\n## Contact\n\nNo contact figure moved (" + identical +
           ": slides' stop steps and distances, bounces' first contacts and apexes, landings' "
           "first contacts and rest offsets, stacked levels' sinks).\n";
  return "\n## Contact\n\nEach slide's stop step and distance, each bounce's first contact step "
         "and apexes, each landing's first contact step and rest offset, each stacked level's "
         "sink, at the scene's step, where they differ (" +
         identical +
         ").\n\n| scene | engine | figure | before -> after |\n"
         "|---|---|---|---|\n" +
         rows;
}

}  // namespace

ResultSet load_result_set(const std::string& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError(dir, 0, "", "does not exist or is not a directory of baseline files");
  ResultSet set;
  set.dir = dir;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".txt") continue;
    const std::string path = entry.path().string();
    Baseline b = read_baseline(path);  // a link, device, FIFO or folder here is refused
    check_baseline_file_name(b, path);
    set.runs[entry.path().filename().string()] = std::move(b);
  }
  return set;
}

Movement classify(const Baseline* before, const Baseline* after) {
  if (!before) return Movement::only_after;
  if (!after) return Movement::only_before;
  if (!before->skipped.empty() || !after->skipped.empty())
    return before->skipped.empty() == after->skipped.empty() ? Movement::skipped : Movement::moved;
  // The hash is what the file claims; identical means the stored samples agree to the bit too.
  if (before->hash == after->hash && before->status == after->status) {
    const SampleDiff same = diff_samples(before->samples, after->samples, 0.0);
    if (same.incomparable.empty() && same.first_step < 0) return Movement::identical;
  }
  const double tol = regression_tolerance(after->scalar);
  const SampleDiff d = diff_samples(before->samples, after->samples, tol);
  if (!d.incomparable.empty() || d.first_step >= 0 || before->status != after->status)
    return Movement::moved;
  return sweep_moved(*before, *after, tol) ? Movement::moved : Movement::within_tolerance;
}

const char* to_string(Movement m) {
  switch (m) {
    case Movement::identical:
      return "identical";
    case Movement::within_tolerance:
      return "within tolerance";
    case Movement::moved:
      return "**moved**";
    case Movement::only_before:
      return "only before";
    case Movement::only_after:
      return "only after";
    case Movement::skipped:
      return "skipped";
  }
  return "?";
}

std::string diff_markdown(const ResultSet& before, const ResultSet& after) {
  std::set<std::string> files;
  for (const auto& [file, b] : before.runs) files.insert(file);
  for (const auto& [file, b] : after.runs) files.insert(file);
  std::string rows;
  int moved = 0;
  for (const std::string& file : files) {
    const auto b = before.runs.find(file), a = after.runs.find(file);
    const Baseline* pb = b == before.runs.end() ? nullptr : &b->second;
    const Baseline* pa = a == after.runs.end() ? nullptr : &a->second;
    moved += classify(pb, pa) == Movement::moved;
    rows += summary_row(pb, pa);
  }
  std::string out = "# dropcheck diff\n\nBefore: `" + before.dir + "`, after: `" + after.dir +
                    "`. " + std::to_string(moved) + " of " + std::to_string(files.size()) +
                    " scene/engine runs moved beyond tolerance (" +
                    g3_or_dash(regression_tolerance(Scalar::f64)) + " m for f64, " +
                    g3_or_dash(regression_tolerance(Scalar::f32)) + " m for f32).\n\n";
  out +=
      "| scene | engine | verdict | max \\|dx\\| | first step over tolerance | hash before -> "
      "after |\n";
  out += "|---|---|---|---:|---|---|\n" + rows;
  return out + contact_section(before, after) + curves_section(before, after);
}

}  // namespace dropcheck
