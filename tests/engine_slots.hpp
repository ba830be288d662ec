// Engine slots for a test, as the command line makes them (harness/cli/cmd_report.cpp): each
// name's factory, or none with the reason it is not in this build.
#pragma once

#include <string>
#include <vector>

#include "harness/core/registry.hpp"
#include "harness/study/evaluate.hpp"

namespace dropcheck::testing {

// The registry's factory for `name`.
inline EngineFactory factory(const std::string& name) {
  return [name] { return make_engine(name); };
}

inline std::vector<EngineSlot> slots(const std::vector<std::string>& names) {
  std::vector<EngineSlot> out;
  for (const std::string& name : names) {
    const std::string why = engine_unavailable_reason(name);
    out.push_back({name, why.empty() ? factory(name) : EngineFactory(), why});
  }
  return out;
}

}  // namespace dropcheck::testing
