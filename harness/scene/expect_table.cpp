#include "harness/scene/expect_table.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>
#include <string_view>

#include "harness/core/number_format.hpp"
#include "harness/scene/toml_ascii.hpp"

namespace dropcheck {
namespace {

// One figure as read, with the node it came from (for the line of a later message).
struct ReadFigure {
  ExpectedFigure figure;
  const toml::node* node = nullptr;
};
using Figures = std::map<std::string, ReadFigure>;  // "name" or "body.name"

bool is_lower(char c) {
  return c >= 'a' && c <= 'z';
}
bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

// [a-z][a-z0-9_]*: the name of a figure, or of a body whose figures a table holds.
bool is_figure_name(std::string_view name) {
  if (name.empty() || !is_lower(name[0])) return false;
  return std::all_of(name.begin(), name.end(),
                     [](char c) { return is_lower(c) || is_digit(c) || c == '_'; });
}

// -?D+(.D+)?(e[+-]?D+)? with D a digit: a figure as a description writes it (62, 2.5510, -0.015,
// 1e-5), not 0x3e, 1_000, +5 or 1E5.
bool is_plain_decimal(std::string_view t) {
  std::size_t i = 0;
  const auto digits = [&] {
    const std::size_t from = i;
    while (i < t.size() && is_digit(t[i])) ++i;
    return i > from;
  };
  if (i < t.size() && t[i] == '-') ++i;
  if (!digits()) return false;
  if (i < t.size() && t[i] == '.' && (++i, !digits())) return false;
  if (i < t.size() && t[i] == 'e') {
    ++i;
    if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
    if (!digits()) return false;
  }
  return i == t.size();
}

// The value text at `at` (toml++'s 1-based line and column in `ascii`, the text it parsed): from
// there to the next space, tab, comma, '}', ']', '#' or line end. Empty when `at` is not in it.
std::string_view written_at(std::string_view ascii, const toml::source_position& at) {
  std::size_t line_start = 0;
  for (toml::source_index line = 1; line < at.line; ++line) {
    line_start = ascii.find('\n', line_start);
    if (line_start == std::string_view::npos) return {};
    ++line_start;
  }
  const std::size_t start = line_start + at.column - 1;
  if (at.column == 0 || start > ascii.size() || ascii.find('\n', line_start) < start) return {};
  const std::size_t end = ascii.find_first_of(" \t,}]#\r\n", start);
  return ascii.substr(start, end == std::string_view::npos ? end : end - start);
}

// One figure: a finite number (an integer exactly a double), with its text as written. A figure
// set in code (a sweep's axis, harness/plan/axes.cpp) has no source text: its shortest text.
ExpectedFigure read_figure(const Reader& r, const std::string& key, const toml::node& n,
                           std::string_view ascii) {
  ExpectedFigure f;
  f.value = r.number(key, n);
  if (n.source().begin.line == 0) {
    f.text = shortest(f.value);
    return f;
  }
  const std::string_view text = written_at(ascii, n.source().begin);
  if (!is_plain_decimal(text))
    r.fail(
        key,
        "write a figure as a plain decimal number (62, 2.5510, -0.015, 1e-5), got " + excerpt(text),
        &n);
  f.text = std::string(text);
  if (std::strtod(f.text.c_str(), nullptr) != f.value)
    r.fail(key, "its text " + excerpt(text) + " does not read back as its value", &n);
  return f;
}

void check_name(const Reader& r, const std::string& name, const toml::node& n) {
  if (!is_figure_name(name))
    r.fail(escape_controls(name),
           "a name in [expect] is lower-case letters, digits and '_', starting with a letter "
           "([a-z][a-z0-9_]*)",
           &n);
}

// The figures of one table of [expect] into `out`, each named `prefix` + its key: the scene's own
// (prefix "", where a table holds a body's figures) or one body's (prefix "<body>.").
void read_table(const Reader& r, const std::string& prefix, std::string_view ascii, const Scene& s,
                Figures& out) {
  for (const auto& [k, v] : r.table()) {
    const std::string name(k.str());
    check_name(r, name, v);
    if (prefix.empty() && v.is_table()) {
      const auto named = [&](const Body& b) { return b.name == name; };
      if (std::none_of(s.bodies.begin(), s.bodies.end(), named))
        r.fail(name,
               "no body named " + excerpt(name) + " (a table in [expect] holds a body's figures)",
               &v);
      read_table(Reader(r.file(), *v.as_table(), r.path(name)), name + ".", ascii, s, out);
      continue;
    }
    if (out.size() >= kMaxExpectedFigures)
      r.fail(name, "more than " + std::to_string(kMaxExpectedFigures) + " figures in [expect]", &v);
    out[prefix + name] = {read_figure(r, name, v, ascii), &v};
  }
}

// `description` with each {name} replaced by that figure's text; the names quoted go to `quoted`.
std::string quote(const Reader& r, const std::string& description, const Figures& figures,
                  std::set<std::string>& quoted) {
  std::string out;
  for (std::size_t i = 0; i < description.size(); ++i) {
    if (description[i] == '}') {
      const std::size_t from = i > 30 ? i - 30 : 0;
      r.fail("description", "a '}' that closes no {placeholder}: " +
                                excerpt(description.substr(from, i + 1 - from)));
    }
    if (description[i] != '{') {
      out += description[i];
      continue;
    }
    const std::size_t close = description.find('}', i);
    if (close == std::string::npos)
      r.fail("description", "a '{' never closed: " + excerpt(description.substr(i)));
    const std::string name = description.substr(i + 1, close - i - 1);
    const auto f = figures.find(name);
    if (f == figures.end())
      r.fail("description",
             excerpt("{" + name + "}") + " names no figure of [expect] (write it there)");
    out += f->second.figure.text;
    quoted.insert(name);
    i = close;
  }
  return out;
}

// Every figure of `figures` is among those the description quotes.
void check_quoted(const Reader& expect, const Figures& figures,
                  const std::set<std::string>& quoted) {
  for (const auto& [name, f] : figures)
    if (!quoted.count(name))
      expect.fail(name, "the description never quotes it (write {" + name + "} where it states it)",
                  f.node);
}

}  // namespace

void load_expect(const Reader& top, const std::string& text, Scene& scene) {
  Figures figures;
  std::set<std::string> quoted;
  const toml::node* n = top.node("expect");
  if (!n) {
    scene.description = quote(top, scene.description, figures, quoted);
    return;
  }
  if (!n->is_table()) top.fail("expect", "expected a table [expect] of figures", n);
  const Reader expect(top.file(), *n->as_table(), "expect");
  read_table(expect, "", toml_as_ascii(text, top.file()), scene, figures);
  scene.description = quote(top, scene.description, figures, quoted);
  check_quoted(expect, figures, quoted);
  for (const auto& [name, f] : figures) scene.expect[name] = f.figure;
}

}  // namespace dropcheck
