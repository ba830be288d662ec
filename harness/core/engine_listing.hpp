// What the harness knows of every engine, compiled into this build or not: the rows of the one list
// of engines, adapters/engines.txt, as adapters/CMakeLists.txt found their libraries
// (engine_listing.cpp reads the table it generates). Making an engine is the registry's
// (harness/core/registry.hpp).
#pragma once

#include <string>
#include <vector>

namespace dropcheck {

// One engine of adapters/engines.txt as this build sees it.
struct EngineListing {
  std::string name;
  bool compiled_in = false;
  // Nominal ns per body-step of its bare loop, sizing the timing plan (harness/timing/timing.cpp).
  double nominal_ns_per_body_step = 0.0;
  // The same in a scene with contacts, where colliding costs most of a step.
  double nominal_contact_ns_per_body_step = 0.0;
  // The report's slowdown alert threshold (harness/report/timing_record.cpp); 0 where unmeasured.
  double slowdown_threshold = 0.0;
  std::string packages;  // the Debian packages its library needs, comma-separated; "" for none
  std::string option;    // the CMake option that builds its adapter; "" for none
};

// Every engine dropcheck knows, in report order, whether or not it is compiled in.
const std::vector<EngineListing>& engine_listings();

// The listing of `name`; nullptr for an engine not in the list (an external one).
const EngineListing* find_engine_listing(const std::string& name);

}  // namespace dropcheck
