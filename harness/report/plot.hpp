// Plots for the report: SVG made by gnuplot (Debian's gnuplot-nox). The data go to a file, a
// generated script reads it and writes the SVG beside it under a temporary name, which is renamed
// into place only when gnuplot succeeded. Everything written is deterministic (fixed number
// formats, no dates), so the same data give byte-identical SVGs.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace dropcheck {

// One line of a plot: (x, y) points, optionally labelled ("1/60" next to each point).
struct PlotSeries {
  std::string title;
  std::vector<double> x, y;
  std::vector<std::string> labels;  // empty, or one per point
  int color = 0;  // index into a fixed palette (the same engine gets the same colour in every plot)
  int dash = 0;   // 0 solid; 1, 2, ... dashed patterns (e.g. one per body)
  double width = 1.5;  // line width; draw coincident lines widest first so that each stays visible
};

struct PlotSpec {
  std::string title, xlabel, ylabel;
  bool log_x = false, log_y = false;
  bool points = false;  // a marker at every point (sparse data such as a sweep)
  std::vector<PlotSeries> series;
};

// The terminal every plot uses, for the report's note on how plots are made.
inline constexpr const char* kPlotTerminal = "set terminal svg size 800,480 dynamic font 'sans,11'";

// Longest user text (characters) a plot shows; longer text is cut and ends in "...".
inline constexpr std::size_t kPlotTextMax = 200;

// User text (scene, body and engine names, step labels) made safe to show in a plot: every control
// character (line breaks, NUL, ...) becomes a space, each byte that is not valid UTF-8 becomes '?',
// and text longer than kPlotTextMax characters is cut. With gnuplot's single quotes (backticks and
// escapes are not expanded there) no character of the result can end a string or start a command.
std::string plot_text(const std::string& text);

// The data file: one block per drawable series (two blank lines apart), rows "x y [\"label\"]" in
// %.9g; points that cannot be drawn (non-finite, or <= 0 on a log axis) are left out.
std::string gnuplot_data(const PlotSpec& spec);

// The gnuplot script that reads `data_file` and writes `svg_file` (paths relative to gnuplot's
// working directory). Titles are quoted for gnuplot and shown literally (noenhanced).
std::string gnuplot_script(const PlotSpec& spec, const std::string& data_file,
                           const std::string& svg_file);

// True when the spec has at least one point gnuplot can draw.
bool drawable(const PlotSpec& spec);

// Renders `spec` into `dir`/`svg_name` via gnuplot run in `dir`. Returns "" on success, else why
// the plot was not made ("gnuplot not found", gnuplot's error); no partial SVG is left behind.
std::string render_plot(const PlotSpec& spec, const std::string& dir, const std::string& svg_name);

}  // namespace dropcheck
