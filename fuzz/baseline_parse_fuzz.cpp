// Fuzz target: the baseline parser (harness/guard/baseline_parse.cpp) on arbitrary bytes, checked
// by round_trip.hpp: parse or InputError, and a baseline that parses prints (baseline_to_text) to
// a text that parses to a baseline printing the same. A crash, sanitizer report or broken round
// trip is a bug.
#include "fuzz/round_trip.hpp"
#include "harness/guard/baseline.hpp"
#include "harness/guard/baseline_io.hpp"
#include "harness/guard/baseline_parse.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return dropcheck::fuzz::round_trip(data, size, dropcheck::parse_baseline,
                                     dropcheck::baseline_to_text);
}
