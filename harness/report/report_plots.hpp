// The report's plots, as data (report_plots.cpp); drawing them is plot.cpp's job.
#pragma once

#include <string>
#include <vector>

#include "harness/report/plot.hpp"

namespace dropcheck {

struct ReportInput;

// One plot of the report: its file name (in the report's directory) and what to draw.
struct ReportPlot {
  std::string file;
  std::string alt;  // the Markdown image's alt text
  PlotSpec spec;
};

// Every plot the report for these scenes draws, per scene in order (report_plots.cpp).
std::vector<std::vector<ReportPlot>> report_plots(const ReportInput& input);

}  // namespace dropcheck
