#include "harness/report/report_format.hpp"

#include <algorithm>
#include <cmath>

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

std::string cell(double v) {
  return std::isnan(v) ? kNone : g3(v);
}

std::string length(double metres) {
  return std::isnan(metres) ? kNone : format_length(metres);
}

std::string order(double p) {
  return std::isfinite(p) ? fixed(p, 2) : kNone;
}

std::string percent(double fraction) {
  return std::isfinite(fraction) ? printf_string("%+.0f%%", 100.0 * fraction) : kNone;
}

std::string when(double t) {
  return t < 0.0 ? "never" : sig(t, 4);
}

std::string literal_stars(const std::string& md) {
  std::string out;
  out.reserve(md.size() + md.size() / 32);
  bool code = false;  // inside a `code span` (a line never leaves one open)
  for (std::size_t i = 0; i < md.size(); ++i) {
    const char c = md[i];
    if (c == '`') code = !code;
    if (c == '\n') code = false;
    const bool pair = (i > 0 && md[i - 1] == '*') || (i + 1 < md.size() && md[i + 1] == '*');
    if (c == '*' && !code && !pair && !(i > 0 && md[i - 1] == '\\')) out += '\\';
    out += c;
  }
  return out;
}

}  // namespace dropcheck
