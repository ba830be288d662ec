// Formatting for the Markdown report: fixed number formats and tables, so that the same results
// always give the same bytes (docs/design.md: reports byte-stable, fixed formatting, sorted rows).
#pragma once

#include <string>
#include <vector>

#include "harness/core/number_format.hpp"
#include "harness/io/file_slug.hpp"

namespace dropcheck {

// A Markdown table. `align` holds 'l' or 'r' per column (numbers right-aligned); its last letter
// applies to the columns beyond it.
class MarkdownTable {
 public:
  MarkdownTable(std::vector<std::string> header, std::string align);
  // Appends a row; cells are escaped ('|' -> '\|'); missing cells are left empty.
  void add(std::vector<std::string> cells);
  bool empty() const { return rows_.empty(); }
  // The table, one line per row, ending with a newline.
  std::string str() const;

 private:
  std::vector<std::string> header_;
  std::string align_;
  std::vector<std::vector<std::string>> rows_;
};

// `md` with every lone '*' outside a code span escaped ('\*'): the report writes products as m*g
// and h*v, which Markdown would otherwise read as emphasis (a pair "**" is left for bold).
std::string literal_stars(const std::string& md);

// The dash shown where a figure does not exist.
inline constexpr const char* kNone = "—";

// A figure in a table cell: g3 (number_format.hpp), "—" for NaN.
std::string cell(double v);

// A length with its unit (number_format.hpp format_length); "—" for NaN.
std::string length(double metres);

// An observed order "%.2f"; "—" for NaN (zero error, nothing to measure).
std::string order(double p);

// A fraction as a percentage "%.0f%%" ("+35%" style with sign); "—" for NaN.
std::string percent(double fraction);

// A time t (s) of a first divergence; "never" when negative.
std::string when(double t);

}  // namespace dropcheck
