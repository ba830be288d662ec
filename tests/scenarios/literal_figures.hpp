// The rule for the figures a description writes itself, outside its {placeholders} (docs/design.md,
// "Scenario files"): each is a number the scene file sets, so that no figure of a description goes
// unchecked: a placeholder's by its [expect] quantity, any other as one of the scene's inputs.
//
// A figure is a number standing as a word: -?D+(.D+)?(e-?D+)? with D a digit, or 1/D+ (a step).
// Not figures: a digit inside a word (Box2D), a unit's power (m/s^2), the 1 of 1/s; and
// "docs/engines.md section N" is a citation, whose section must exist.
//
// The inputs: every number the file sets outside description, name, [expect] and [[published]]
// (arrays' elements too); a step written "1/N" sets 1/N s and N (its rate in Hz), one written
// "0.1" sets 0.1. A figure is an input when it equals one as a double or, written unsigned, equals
// its magnitude (9.8 for gravity = [0.0, -9.8, 0.0]).
#pragma once

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "harness/scene/toml_reader.hpp"

namespace dropcheck::testing {
namespace literal {

inline bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
inline bool is_word(char c) {
  return is_digit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}

// A figure as written ("-2", "1e-5", "1/60") and its value.
struct Figure {
  std::string text;
  double value = 0.0;
};

// "## 5." headings of docs/engines.md, the sections descriptions may cite.
inline bool engines_md_has_section(const std::string& number) {
  std::ifstream in(DROPCHECK_SOURCE_DIR "/docs/engines.md");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("## " + number + ". ", 0) == 0) return true;
  return false;
}

// The end of the number at text[i] (a digit): D+(.D+)?(e-?D+)?(/D+)?.
inline std::size_t number_end(const std::string& t, std::size_t i) {
  const auto digits = [&](std::size_t j) {
    while (j < t.size() && is_digit(t[j])) ++j;
    return j;
  };
  i = digits(i);
  if (i + 1 < t.size() && t[i] == '.' && is_digit(t[i + 1])) i = digits(i + 1);
  if (i + 1 < t.size() && t[i] == 'e') {
    const std::size_t sign = t[i + 1] == '-' ? 1 : 0;
    if (i + 1 + sign < t.size() && is_digit(t[i + 1 + sign])) i = digits(i + 1 + sign);
  }
  if (i + 1 < t.size() && t[i] == '/' && is_digit(t[i + 1])) i = digits(i + 1);
  return i;
}

// The figure whose text is t[from, to): "1/N" is 1/N, any other its decimal value.
inline Figure figure(const std::string& t, std::size_t from, std::size_t to) {
  const std::string text = t.substr(from, to - from);
  const std::size_t slash = text.find('/');
  const double value = slash == std::string::npos
                           ? std::strtod(text.c_str(), nullptr)
                           : 1.0 / std::strtod(text.c_str() + slash + 1, nullptr);
  return {text, value};
}

// The figures `description` writes outside its {placeholders}; a cited section that docs/engines.md
// lacks goes to `problems`.
inline std::vector<Figure> figures_of(const std::string& description,
                                      std::vector<std::string>& problems) {
  const std::string citation = "docs/engines.md section ";
  std::vector<Figure> out;
  for (std::size_t i = 0; i < description.size();) {
    const char c = description[i];
    if (c == '{') {  // a placeholder: checked by its quantity (the loader saw it closed)
      i = description.find('}', i);
      if (i == std::string::npos) break;
      continue;
    }
    if (!is_digit(c)) {
      ++i;
      continue;
    }
    const std::size_t end = number_end(description, i);
    const char before = i > 0 ? description[i - 1] : ' ';
    const bool in_word = is_word(before) || before == '^' || before == '.' ||
                         (end < description.size() && is_word(description[end]));
    const bool per_unit = end + 1 < description.size() && description[end] == '/' &&
                          !is_digit(description[end + 1]);  // the 1 of 1/s
    const bool cited = i >= citation.size() &&
                       description.compare(i - citation.size(), citation.size(), citation) == 0;
    if (cited && !engines_md_has_section(description.substr(i, end - i)))
      problems.push_back("cites " + citation + description.substr(i, end - i) +
                         ", which docs/engines.md does not have");
    const bool negative =
        before == '-' && (i < 2 || description[i - 2] == ' ' || description[i - 2] == '(');
    if (!in_word && !per_unit && !cited) out.push_back(figure(description, i - negative, end));
    i = end;
    while (in_word && i < description.size() && is_word(description[i])) ++i;
  }
  return out;
}

// Every number `n` (at `key`) sets, into `out`; tables and arrays through their elements.
inline void collect_inputs(const toml::node& n, const std::string& key, std::vector<double>& out) {
  if (const auto* t = n.as_table()) {
    for (const auto& [k, v] : *t) collect_inputs(v, std::string(k.str()), out);
  } else if (const auto* a = n.as_array()) {
    for (const toml::node& e : *a) collect_inputs(e, key, out);
  } else if (n.is_number()) {
    out.push_back(*n.value<double>());
  } else if (n.is_string() && (key == "timestep" || key == "timesteps")) {
    const std::string text = *n.value<std::string>();
    if (text.rfind("1/", 0) == 0) out.push_back(std::strtod(text.c_str() + 2, nullptr));
    out.push_back(figure(text, 0, text.size()).value);
  }
}

// The scene's inputs: every number its file sets but in description, name, [expect], [[published]].
inline std::vector<double> inputs_of(const toml::table& root) {
  std::vector<double> out;
  for (const auto& [k, v] : root)
    if (k.str() != "description" && k.str() != "name" && k.str() != "expect" &&
        k.str() != "published")
      collect_inputs(v, std::string(k.str()), out);
  return out;
}

inline bool is_input(const Figure& f, const std::vector<double>& inputs) {
  for (double x : inputs)
    if (f.value == x || (f.text[0] != '-' && f.value == std::abs(x))) return true;
  return false;
}

}  // namespace literal

// Every figure of the description of the scene file `text` (read as `path`) that is no input of
// it, and every citation of a section docs/engines.md lacks, as a sentence.
inline std::vector<std::string> literal_figure_problems(const std::string& text,
                                                        const std::string& path) {
  const toml::table root = parse_toml(text, path);
  const std::string description = root["description"].value_or(std::string());
  std::vector<std::string> problems;
  const std::vector<double> inputs = literal::inputs_of(root);
  for (const literal::Figure& f : literal::figures_of(description, problems))
    if (!literal::is_input(f, inputs))
      problems.push_back("\"" + f.text +
                         "\" in the description is no number the scene file sets: give it an "
                         "[expect] name and write {name}, or write the input as the file does");
  return problems;
}

}  // namespace dropcheck::testing
