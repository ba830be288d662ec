// Fuzz target: the plan reader (harness/plan/plan.cpp) and what a shard does with a plan before it
// runs anything: every cell's key, and the first cells' scenes set up from the plan's scene texts
// and axis values (harness/plan/axes.cpp: key paths such as "body.cube.mass", named axes). Any
// input must be refused with InputError or set up, a refusal's message short and inert (no control
// character, no invalid UTF-8); any other exception, a crash or a sanitizer report is a bug. The
// hash check is off: a fuzzer cannot forge FNV-1a on purpose, a user can.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "harness/core/input_error.hpp"
#include "harness/plan/axes.hpp"
#include "harness/plan/plan.hpp"

namespace {

void require_inert(const dropcheck::InputError& e) {
  const std::string message = e.what();
  if (message.size() > 1024 || dropcheck::find_unsafe_byte(message) != std::string::npos)
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dropcheck::Plan plan;
  try {
    plan = dropcheck::parse_plan(text, "fuzz.plan", false);
  } catch (const dropcheck::InputError& e) {
    require_inert(e);
    return 0;
  }
  const std::size_t cells = plan.cell_count();
  for (std::size_t i = 0; i < cells && i < 8; ++i) {
    const dropcheck::Cell c = plan.cell(i);
    std::vector<std::string> values;
    for (std::size_t k = 0; k < plan.axes.size(); ++k)
      values.push_back(plan.axes[k].values[c.values[k]]);
    try {
      const dropcheck::PlanScene& s = plan.scenes[c.scene];
      (void)dropcheck::setup_cell(s.text, s.file, plan.engines[c.engine], plan.axes, values);
    } catch (const dropcheck::InputError&) {
    }
  }
  return 0;
}
