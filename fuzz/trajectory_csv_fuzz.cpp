// Fuzz target: the trajectory CSV reader of `identify --trajectory` (harness/io/trajectory_csv.cpp)
// on arbitrary bytes, checked by round_trip.hpp: parse or InputError, and runs that parse print
// (trajectories_to_csv, what `run --csv` writes) to a text that parses to runs printing the same.
// Beyond the round trip: every number read is finite, and a refusal's message is short and inert
// (no control character, no invalid UTF-8). A crash, sanitizer report or broken check is a bug.
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "fuzz/round_trip.hpp"
#include "harness/io/trajectory_csv.hpp"
#include "harness/io/trajectory_io.hpp"

namespace {

std::vector<dropcheck::Trajectory> parse(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  std::vector<dropcheck::Trajectory> runs;
  try {
    runs = dropcheck::parse_trajectories_csv(in, file);
  } catch (const dropcheck::InputError& e) {
    const std::string message = e.what();
    if (message.size() > 1024 || dropcheck::find_unsafe_byte(message) != std::string::npos)
      std::abort();
    throw;
  }
  for (const dropcheck::Trajectory& t : runs) {
    if (!std::isfinite(t.h)) std::abort();
    for (const dropcheck::BodyState& s : t.states)
      if (!s.position.allFinite() || !s.velocity.allFinite()) std::abort();
  }
  return runs;
}

std::string print(const std::vector<dropcheck::Trajectory>& runs) {
  return dropcheck::trajectories_to_csv(runs);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return dropcheck::fuzz::round_trip(data, size, parse, print);
}
