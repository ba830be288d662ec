// Reading JSON text with a bounded nesting depth. nlohmann's parser keeps its own stack, but
// dumping or destroying a value, and any code that walks it, recurses once per level: a record
// nesting 10^6 arrays would overflow the stack. dropcheck's own files (plans, records, timings)
// nest at most 5 deep; nothing deeper is read.
#pragma once

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>

namespace dropcheck {

// Deepest nesting of arrays and objects read.
inline constexpr int kMaxJsonDepth = 64;

// `text` parsed as J (nlohmann::json or nlohmann::ordered_json). Throws J's parse_error on a
// syntax error, and std::invalid_argument, saying so, when arrays and objects nest deeper than
// kMaxJsonDepth (the parse stops there).
template <class J>
J parse_json(std::string_view text) {
  return J::parse(text, [](int depth, typename J::parse_event_t event, J&) {
    if (depth >= kMaxJsonDepth &&
        (event == J::parse_event_t::object_start || event == J::parse_event_t::array_start))
      throw std::invalid_argument("arrays and objects nest deeper than " +
                                  std::to_string(kMaxJsonDepth) + " levels");
    return true;
  });
}

}  // namespace dropcheck
