// The check shared by the fuzz targets of readers with a writer: any input must parse or be refused
// with InputError, and what parses must print, parse again and print the same text (the writer and
// the reader agree on everything the reader accepts). Anything else aborts: a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "harness/core/input_error.hpp"

namespace dropcheck::fuzz {

// `parse(text, file)` -> T throwing InputError; `print(T)` -> std::string.
template <class Parse, class Print>
int round_trip(const std::uint8_t* data, std::size_t size, Parse parse, Print print) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  decltype(parse(text, "")) value;
  try {
    value = parse(text, "fuzz.input");
  } catch (const InputError&) {
    return 0;
  }
  const std::string once = print(value);
  if (print(parse(once, "fuzz.input")) != once) std::abort();  // the round trip changed it
  return 0;
}

}  // namespace dropcheck::fuzz
