#include "harness/io/json_text.hpp"

#include <stdexcept>

namespace dropcheck {

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

template <class J>
std::string json_text(const J& value, int indent, BadUtf8 bad) {
  return value.dump(
      indent, ' ', false,
      bad == BadUtf8::replace ? J::error_handler_t::replace : J::error_handler_t::strict);
}

template nlohmann::json parse_json<nlohmann::json>(std::string_view);
template nlohmann::ordered_json parse_json<nlohmann::ordered_json>(std::string_view);
template std::string json_text<nlohmann::json>(const nlohmann::json&, int, BadUtf8);
template std::string json_text<nlohmann::ordered_json>(const nlohmann::ordered_json&, int, BadUtf8);

}  // namespace dropcheck
