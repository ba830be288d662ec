// JSON text in and out, for nlohmann::json and nlohmann::ordered_json, parsed and written in one
// translation unit (json_text.cpp): nlohmann's parser and serializer are templates, and each
// source that instantiated them cost some 15 s of compiling under the sanitizers.
//
// Reading bounds the nesting depth. nlohmann's parser keeps its own stack, but dumping or
// destroying a value, and any code that walks it, recurses once per level: a record nesting 10^6
// arrays would overflow the stack. dropcheck's own files (plans, records, timings) nest at most 5
// deep; nothing deeper is read.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace dropcheck {

// Deepest nesting of arrays and objects read.
inline constexpr int kMaxJsonDepth = 64;

// `text` parsed as J (nlohmann::json or nlohmann::ordered_json). Throws J's parse_error on a
// syntax error, and std::invalid_argument, saying so, when arrays and objects nest deeper than
// kMaxJsonDepth (the parse stops there).
template <class J>
J parse_json(std::string_view text);

// What a string that is not UTF-8 does to the text written: nlohmann's type_error, or U+FFFD in
// place of each bad byte (for names that came from engines and users).
enum class BadUtf8 { throw_error, replace };

// J's text: on one line (indent < 0) or `indent` spaces a level. Strings are escaped; NaN and Inf
// are written null.
template <class J>
std::string json_text(const J& value, int indent = -1, BadUtf8 bad = BadUtf8::throw_error);

// J's text on one line, escaped by construction, a byte that is not UTF-8 written as U+FFFD
// instead of breaking the file: for records that hold names from engines and users.
template <class J>
std::string json_line(const J& value) {
  return json_text(value, -1, BadUtf8::replace);
}

extern template nlohmann::json parse_json<nlohmann::json>(std::string_view);
extern template nlohmann::ordered_json parse_json<nlohmann::ordered_json>(std::string_view);
extern template std::string json_text<nlohmann::json>(const nlohmann::json&, int, BadUtf8);
extern template std::string json_text<nlohmann::ordered_json>(const nlohmann::ordered_json&, int,
                                                              BadUtf8);

}  // namespace dropcheck
