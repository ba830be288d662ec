#include "harness/report/report_format.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>

#include "harness/measure/attribution.hpp"

namespace dropcheck {

MarkdownTable::MarkdownTable(std::vector<std::string> header, std::string align)
    : header_(std::move(header)), align_(align.empty() ? "l" : std::move(align)) {}

void MarkdownTable::add(std::vector<std::string> cells) {
  cells.resize(header_.size());
  for (std::string& c : cells) {
    std::string escaped;
    for (char ch : c) escaped += ch == '|' ? std::string("\\|") : std::string(1, ch);
    c = escaped;
  }
  rows_.push_back(std::move(cells));
}

std::string MarkdownTable::str() const {
  auto line = [](const std::vector<std::string>& cells) {
    std::string s = "|";
    for (const std::string& c : cells) s += " " + c + " |";
    return s + "\n";
  };
  std::string out = line(header_) + "|";
  for (std::size_t i = 0; i < header_.size(); ++i)
    out += align_[std::min(i, align_.size() - 1)] == 'r' ? "---:|" : "---|";
  out += "\n";
  for (const auto& r : rows_) out += line(r);
  return out;
}

std::string strf(const char* format, ...) {
  char buf[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return buf;
}

std::string g3(double v) {
  if (std::isnan(v)) return kNone;
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return strf("%.3g", v);
}

std::string length(double metres) {
  return std::isnan(metres) ? kNone : format_length(metres);
}

std::string order(double p) {
  return std::isfinite(p) ? strf("%.2f", p) : kNone;
}

std::string percent(double fraction) {
  return std::isfinite(fraction) ? strf("%+.0f%%", 100.0 * fraction) : kNone;
}

std::string when(double t) {
  return t < 0.0 ? "never" : strf("%.4g", t);
}

}  // namespace dropcheck
