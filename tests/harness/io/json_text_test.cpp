// Tests harness/io/json_text.hpp: JSON nests at most kMaxJsonDepth levels, refused past that
// before the value is walked (a million levels once overflowed the stack in dump()).
#include "harness/io/json_text.hpp"

#include <catch2/catch.hpp>

using namespace dropcheck;
using Catch::Matchers::Contains;

namespace {

std::string nested(std::size_t levels, char open = '[', char close = ']') {
  return std::string(levels, open) + std::string(levels, close);
}

}  // namespace

TEST_CASE("parse_json reads kMaxJsonDepth levels and refuses one more", "[limits]") {
  CHECK(parse_json<nlohmann::json>(nested(kMaxJsonDepth)).is_array());
  CHECK_THROWS_AS(parse_json<nlohmann::json>(nested(kMaxJsonDepth + 1)), std::invalid_argument);
  CHECK_THROWS_WITH(parse_json<nlohmann::ordered_json>("{\"a\":" + nested(1000000) + "}"),
                    Contains("nest deeper than 64 levels"));
  // Objects count as levels too; a syntax error is nlohmann's own.
  std::string objects;
  for (int i = 0; i < 100; ++i) objects += "{\"a\":";
  objects += "1" + std::string(100, '}');
  CHECK_THROWS_AS(parse_json<nlohmann::json>(objects), std::invalid_argument);
  CHECK_THROWS_AS(parse_json<nlohmann::json>("[1,"), nlohmann::json::parse_error);
}
