#include "harness/report/report_sweep.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/timestep.hpp"
#include "harness/core/trajectory_hash.hpp"
#include "harness/io/atomic_file.hpp"
#include "harness/io/file_slug.hpp"
#include "harness/report/plot.hpp"
#include "harness/report/report_format.hpp"
#include "harness/report/report_html.hpp"

namespace dropcheck {
namespace {

// An axis value as a number: a step "1/60" in seconds, anything else as written.
std::optional<double> axis_number(const std::string& name, const std::string& text) {
  if (name == "timestep") {
    std::string why;
    const std::optional<Timestep> h = parse_timestep(text, why);
    return h ? std::optional<double>(h->seconds) : std::nullopt;
  }
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return v;
}

// Log scale for an axis whose values are all > 0 and span more than a factor 10.
bool wants_log(const std::vector<double>& v) {
  if (v.empty()) return false;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *lo > 0.0 && *hi > 10.0 * *lo;
}

struct Group {
  std::string scene, engine;
  std::string slug;  // its maps' file names: one per group (give_slugs)
  std::vector<const SweepCell*> cells;
};

struct Placed {
  const SweepCell* cell;
  double x, y;
};

std::vector<Placed> place(const Group& g) {
  std::vector<Placed> out;
  for (const SweepCell* c : g.cells) {
    if (c->axes.empty()) continue;
    const std::optional<double> x = axis_number(c->axes[0].first, c->axes[0].second);
    const std::optional<double> y =
        c->axes.size() > 1 ? axis_number(c->axes[1].first, c->axes[1].second) : 1.0;
    if (x && y) out.push_back({c, *x, *y});
  }
  return out;
}

PlotSpec frame(const Group& g, const std::vector<Placed>& placed, const std::string& what) {
  PlotSpec p;
  const SweepCell& first = *g.cells.front();
  p.title = g.scene + " / " + g.engine + ": " + what;
  p.xlabel = first.axes[0].first + (first.axes[0].first == "timestep" ? " h (s)" : "");
  p.ylabel = first.axes.size() > 1 ? first.axes[1].first : "";
  std::vector<double> xs, ys;
  for (const Placed& c : placed) xs.push_back(c.x), ys.push_back(c.y);
  p.log_x = wants_log(xs);
  p.log_y = wants_log(ys);
  p.points = true;
  return p;
}

// How each run ended, one series per status, and the theory's largest stable step across it.
PlotSpec stability_map(const Group& g, const std::vector<Placed>& placed) {
  PlotSpec p = frame(g, placed, "how each run ended");
  std::map<std::string, PlotSeries> by_status;
  std::map<double, double> edge;  // y -> theory_max_h
  for (const Placed& c : placed) {
    PlotSeries& s = by_status[c.cell->status];
    s.x.push_back(c.x);
    s.y.push_back(c.y);
    if (c.cell->theory_max_h && std::isfinite(*c.cell->theory_max_h))
      edge[c.y] = *c.cell->theory_max_h;
  }
  int colour = 0;
  for (auto& [status, s] : by_status) {
    s.title = status;
    s.color = status == "ok" ? 2 : status == "skipped" ? 7 : colour++ % 2 == 0 ? 1 : 3;
    p.series.push_back(std::move(s));
  }
  if (!edge.empty() && g.cells.front()->axes[0].first == "timestep") {
    PlotSeries line;
    line.title = "largest stable h, theory";
    line.color = 6;
    line.dash = 1;
    for (const auto& [y, h] : edge) line.x.push_back(h), line.y.push_back(y);
    p.series.push_back(std::move(line));
  }
  return p;
}

// The error against the closed form in decades.
PlotSpec error_map(const Group& g, const std::vector<Placed>& placed) {
  PlotSpec p = frame(g, placed, "max |x - closed form| in decades");
  const char* names[] = {"< 1e-9 m", "1e-9 .. 1e-6 m", "1e-6 .. 1e-3 m", "1e-3 .. 1 m", ">= 1 m"};
  PlotSeries bins[5];
  for (int i = 0; i < 5; ++i) bins[i].title = names[i], bins[i].color = i == 4 ? 1 : i;
  for (const Placed& c : placed) {
    if (c.cell->status != "ok" || !c.cell->error || !std::isfinite(*c.cell->error)) continue;
    const double e = *c.cell->error;
    const int bin = e < 1e-9 ? 0 : e < 1e-6 ? 1 : e < 1e-3 ? 2 : e < 1.0 ? 3 : 4;
    bins[bin].x.push_back(c.x);
    bins[bin].y.push_back(c.y);
  }
  for (PlotSeries& b : bins)
    if (!b.x.empty()) p.series.push_back(std::move(b));
  return p;
}

// User text in a table or heading: controls escaped, cut to 160 bytes.
std::string text_cell(const std::string& s) {
  const std::string t = escape_controls(s);
  return t.size() > 160 ? t.substr(0, 157) + "..." : t;
}

void maps(const Group& g, const std::string& dir, std::ostringstream& md) {
  const std::vector<Placed> placed = place(g);
  if (placed.empty()) {
    md << "No map: the sweep's first axes are not numbers here.\n\n";
    return;
  }
  const std::string& slug = g.slug;
  for (const auto& [spec, name] : {std::pair{stability_map(g, placed), slug + "-stability.svg"},
                                   std::pair{error_map(g, placed), slug + "-error.svg"}}) {
    if (!drawable(spec)) continue;
    const std::string why = render_plot(spec, dir, name);
    md << (why.empty() ? "![" + plot_text(spec.title) + "](" + name + ")\n\n"
                       : "Plot not drawn: " + text_cell(why) + "\n\n");
  }
}

void sweep_failures(const std::vector<SweepCell>& cells, std::ostringstream& md) {
  MarkdownTable t({"cell", "status", "cause"}, "lll");
  std::size_t skipped = 0;
  for (const SweepCell& c : cells) {
    if (c.status == "ok") continue;
    if (c.status == "skipped") {
      ++skipped;
      continue;
    }
    t.add({text_cell(c.key), text_cell(c.status),
           text_cell(c.reason + (c.law_unstable.empty() ? "" : "; " + c.law_unstable))});
  }
  md << "## Cells that did not end ok\n\n";
  md << (t.empty() ? std::string("None.\n") : t.str());
  md << "\n" << skipped << " cells skipped (the engine cannot run them: each record says why).\n\n";
}

void timings(const std::vector<SweepCell>& cells, std::ostringstream& md) {
  std::map<std::pair<std::string, std::string>, std::vector<double>> by;  // (engine, cpu)
  for (const SweepCell& c : cells)
    if (c.ns_per_body_step && std::isfinite(*c.ns_per_body_step))
      by[{c.engine, c.cpu}].push_back(*c.ns_per_body_step);
  if (by.empty()) return;
  md << "## Timings (wall time)\n\nMedian ns per body-step of each engine's cells, per CPU model: "
        "figures from different CPU models are never pooled.\n\n";
  MarkdownTable t({"engine", "CPU", "cells", "median ns per body-step"}, "llrr");
  for (auto& [k, v] : by) {
    std::sort(v.begin(), v.end());
    const double median =
        v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
    t.add({text_cell(k.first), text_cell(k.second), std::to_string(v.size()), cell(median)});
  }
  md << t.str() << "\n";
}

// Each group's file slug. file_slug is not one-to-one ("a b" and "a_b" meet, and so do the pairs
// "a-b"/"c" and "a"/"b-c"): a slug two groups share gets, in each, '~' and 8 hex digits of the
// FNV-1a hash of that group's own scene and engine, so two groups never share a file.
void give_slugs(std::map<std::pair<std::string, std::string>, Group>& groups) {
  std::map<std::string, int> uses;
  for (auto& [k, g] : groups) ++uses[g.slug = file_slug(g.scene + "-" + g.engine)];
  for (auto& [k, g] : groups)
    if (uses[g.slug] > 1) g.slug += "~" + fnv1a_hex(g.scene + '\n' + g.engine).substr(0, 8);
}

}  // namespace

void write_sweep_report(const std::vector<SweepCell>& cells, const std::string& results,
                        const std::string& dir,
                        const std::function<void(const std::string&)>& progress) {
  std::map<std::pair<std::string, std::string>, Group> groups;
  for (const SweepCell& c : cells) {
    Group& g = groups[{c.scene, c.engine}];
    g.scene = c.scene;
    g.engine = c.engine;
    g.cells.push_back(&c);
  }
  give_slugs(groups);
  std::ostringstream md;
  md << "# dropcheck sweep report\n\nGenerated by `dropcheck report --results "
     << text_cell(results) << "`; do not edit by hand. " << cells.size() << " cells of "
     << groups.size()
     << " scene-engine pairs. Each map places a cell by the sweep's first two axes; the first "
        "shows how its run ended, with the largest stable step its engine's law allows drawn "
        "across it where the first axis is the step; the second, its error against the closed "
        "form in decades (cells that ended ok and have one). The records: docs/results.md.\n\n";
  sweep_failures(cells, md);
  timings(cells, md);
  for (const auto& [k, g] : groups) {
    if (progress) progress(escape_controls(g.scene + " / " + g.engine));
    md << "## " << text_cell(g.scene) << " / " << text_cell(g.engine) << "\n\n";
    maps(g, dir, md);
  }
  const std::string text = literal_stars(md.str());
  write_file_atomic(dir + "/README.md", text);
  write_report_html(dir, text, "dropcheck sweep report");
}

}  // namespace dropcheck
