// Fuzz target: the timings record reader (harness/measure/timing_record.cpp, a previous report's
// timings.json) on arbitrary bytes. Any input must parse or be refused with InputError. A record
// that parses must print (timing_json) and that text must parse again to a record that prints the
// same. A crash, sanitizer report or broken round trip is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "harness/core/input_error.hpp"
#include "harness/measure/timing_record.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dropcheck::TimingRecord r;
  try {
    r = dropcheck::parse_timing_record(text, "timings.json");
  } catch (const dropcheck::InputError&) {
    return 0;
  }
  const std::string once = dropcheck::timing_json(r);
  const std::string twice =
      dropcheck::timing_json(dropcheck::parse_timing_record(once, "timings.json"));
  if (once != twice) std::abort();  // the round trip changed the record
  return 0;
}
