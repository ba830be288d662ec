// Fuzz target: the timings record reader (harness/report/timing_record.cpp, a previous report's
// timings.json) on arbitrary bytes, checked by round_trip.hpp: parse or InputError, and a record
// that parses prints (timing_json) to a text that parses to a record printing the same. A crash,
// sanitizer report or broken round trip is a bug.
#include "fuzz/round_trip.hpp"
#include "harness/report/timing_record.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return dropcheck::fuzz::round_trip(data, size, dropcheck::parse_timing_record,
                                     dropcheck::timing_json);
}
