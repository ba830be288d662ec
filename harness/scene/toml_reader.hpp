// Typed reads out of one TOML table for dropcheck's input files (scenes, sweeps): each value
// checked for type, finiteness and exactness, and every failure an InputError naming the file,
// line and key path.
#pragma once

#include <toml++/toml.h>

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>

#include "harness/core/input_error.hpp"
#include "harness/core/number_format.hpp"
#include "harness/core/scene.hpp"
#include "harness/core/timestep.hpp"

namespace dropcheck {

// Parses TOML text (non-ASCII refused with its line: toml_ascii.hpp); a syntax error is an
// InputError naming `path` and the line.
toml::table parse_toml(const std::string& text, const std::string& path);

// A scene from a parsed TOML table, validated as load_scene validates a file (scene_loader.cpp):
// for a sweep cell's scene with its keys set (harness/plan/axes.cpp). `text` is the file's text
// `root` was parsed from, where the [expect] figures' text as written is read.
Scene scene_from_table(const toml::table& root, const std::string& text, const std::string& path);

// 2^53: every integer up to it in magnitude is exactly a double; past it, not all are.
inline constexpr std::int64_t kExactIntegerLimit = std::int64_t{1} << 53;

// Reads typed values out of one TOML table, throwing InputError with the file, line and key path.
class Reader {
 public:
  Reader(const std::string& file, const toml::table& table, std::string prefix)
      : file_(file), table_(table), prefix_(std::move(prefix)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& problem,
                         const toml::node* at = nullptr) const {
    const toml::node* n = at ? at : table_.get(key);
    const int line =
        n ? static_cast<int>(n->source().begin.line) : static_cast<int>(table_.source().begin.line);
    throw InputError(file_, line, path(key), problem);
  }

  std::string path(const std::string& key) const {
    return prefix_.empty() ? key : prefix_ + "." + key;
  }
  bool has(const std::string& key) const { return table_.contains(key); }
  const toml::node* node(const std::string& key) const { return table_.get(key); }

  void only(std::initializer_list<const char*> allowed) const {
    for (const auto& [k, v] : table_) {
      bool ok = false;
      for (const char* a : allowed) ok = ok || k.str() == a;
      if (!ok) fail(std::string(k.str()), "unknown key", &v);
    }
  }

  double number(const std::string& key, const toml::node& n) const {
    // An integer beyond 2^53 has no exact double (9007199254740993 would silently become ...992).
    if (const std::optional<std::int64_t> i = n.value_exact<std::int64_t>();
        n.is_integer() && i && (*i > kExactIntegerLimit || *i < -kExactIntegerLimit))
      fail(key,
           "the integer " + std::to_string(*i) +
               " is too large to be exactly a double (beyond 2^53); write it as a float",
           &n);
    std::optional<double> v = n.value<double>();
    if (!n.is_number() || !v) fail(key, std::string("expected a number, got ") + type_name(n), &n);
    if (!std::isfinite(*v)) fail(key, "must be finite, got " + format(*v), &n);
    return *v;
  }
  double number(const std::string& key, double fallback) const {
    const toml::node* n = node(key);
    return n ? number(key, *n) : fallback;
  }
  double required_number(const std::string& key) const {
    if (!has(key)) fail(key, "required key is missing");
    return number(key, *node(key));
  }

  Vec3 vec3(const std::string& key, const Vec3& fallback, bool required = false) const {
    const toml::node* n = node(key);
    if (!n) {
      if (required) fail(key, "required key is missing");
      return fallback;
    }
    const toml::array* a = n->as_array();
    if (!a || a->size() != 3) fail(key, "expected an array of 3 numbers [x, y, z]", n);
    Vec3 out;
    for (std::size_t i = 0; i < 3; ++i)
      out[i] = number(key + "[" + std::to_string(i) + "]", *a->get(i));
    return out;
  }

  bool boolean(const std::string& key, bool fallback) const {
    const toml::node* n = node(key);
    if (!n) return fallback;
    if (!n->is_boolean()) fail(key, std::string("expected true or false, got ") + type_name(*n), n);
    return *n->value<bool>();
  }

  std::string string(const std::string& key, const std::string& fallback) const {
    const toml::node* n = node(key);
    if (!n) return fallback;
    if (!n->is_string()) fail(key, std::string("expected a string, got ") + type_name(*n), n);
    return *n->value<std::string>();
  }

  // A name (scene, body): printed on terminals, in reports and file names, so a control character
  // written as a TOML escape ("\u001b[2J", "\t") is refused like a raw one.
  std::string name(const std::string& key, const std::string& fallback) const {
    std::string text = string(key, fallback);
    if (const std::size_t i = find_unsafe_in_line(text); i != std::string::npos) {
      const bool c1 = static_cast<unsigned char>(text[i]) == 0xc2;  // U+0080..U+009F, 2 bytes
      fail(key, "control character " + excerpt(text.substr(i, c1 ? 2 : 1)) +
                    " in a name (names are printed on terminals and in reports)");
    }
    return text;
  }

  Timestep timestep(const std::string& key, const toml::node& n) const {
    std::string text;
    if (n.is_string()) {
      text = *n.value<std::string>();
    } else if (n.is_number()) {
      // Shortest text that reads back to the same double: 0.1 stays "0.1" in messages and output.
      text = shortest(number(key, n));
    } else {
      fail(key, std::string("expected seconds or \"1/N\", got ") + type_name(n), &n);
    }
    std::string why;
    std::optional<Timestep> t = parse_timestep(text, why);
    if (!t) fail(key, why, &n);
    return *t;
  }

  static const char* type_name(const toml::node& n) {
    switch (n.type()) {
      case toml::node_type::string:
        return "a string";
      case toml::node_type::integer:
        return "an integer";
      case toml::node_type::floating_point:
        return "a number";
      case toml::node_type::boolean:
        return "a boolean";
      case toml::node_type::array:
        return "an array";
      case toml::node_type::table:
        return "a table";
      default:
        return "a date or time";
    }
  }
  // A number in a message: 6 significant digits, as the user would print it.
  static std::string format(double v) { return sig(v, 6); }

  const std::string& file() const { return file_; }
  const toml::table& table() const { return table_; }

 private:
  const std::string& file_;
  const toml::table& table_;
  std::string prefix_;
};

// The array of tables at `key` ([[key]]), or nullptr when there is none.
inline const toml::array* array_of_tables(const Reader& r, const std::string& key) {
  const toml::node* n = r.node(key);
  if (!n) return nullptr;
  const toml::array* a = n->as_array();
  if (!a || !a->is_array_of_tables()) r.fail(key, "expected [[" + key + "]] tables", n);
  return a;
}

}  // namespace dropcheck
