#include "harness/core/trajectory.hpp"

namespace dropcheck {

const char* to_string(RunStatus status) {
  switch (status) {
    case RunStatus::ok: return "ok";
    case RunStatus::non_finite: return "non-finite state";
    case RunStatus::engine_error: return "engine error";
  }
  return "?";
}

}  // namespace dropcheck
