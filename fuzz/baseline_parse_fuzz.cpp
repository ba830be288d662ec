// Fuzz target: the baseline parser (harness/guard/baseline_parse.cpp) on arbitrary bytes. Any input
// must parse or be refused with InputError. A baseline that parses must print (baseline_to_text)
// and that text must parse again to a baseline that prints the same: the writer and the reader
// agree on everything the reader accepts. A crash, sanitizer report or broken round trip is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "harness/core/input_error.hpp"
#include "harness/guard/baseline.hpp"
#include "harness/guard/baseline_io.hpp"
#include "harness/guard/baseline_parse.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dropcheck::Baseline b;
  try {
    b = dropcheck::parse_baseline(text, "fuzz.txt");
  } catch (const dropcheck::InputError&) {
    return 0;
  }
  const std::string once = dropcheck::baseline_to_text(b);
  const std::string twice =
      dropcheck::baseline_to_text(dropcheck::parse_baseline(once, "fuzz.txt"));
  if (once != twice) std::abort();  // the round trip changed the baseline
  return 0;
}
