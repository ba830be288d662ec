#include "harness/scene/toml_reader.hpp"

#include "harness/scene/toml_ascii.hpp"

namespace dropcheck {

toml::table parse_toml(const std::string& text, const std::string& path) {
  try {
    return toml::parse(toml_as_ascii(text, path), path);
  } catch (const toml::parse_error& e) {
    throw InputError(path, static_cast<int>(e.source().begin.line), "",
                     "TOML syntax error: " + std::string(e.description()));
  }
}

}  // namespace dropcheck
