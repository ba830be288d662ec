// bare_step_loop: each compiled-in engine's bare stepping loop, by registry name (adapters.hpp).
#include <stdexcept>
#include <utility>

#include "adapters.hpp"

namespace dropcheck {
namespace {

using BareLoop = double (*)(const Scene&, double);

// One row per engine compiled into this build.
const std::pair<const char*, BareLoop> kBareLoops[] = {
    {"ours", bare_seconds_ours_f32},
    {"ours-f64", bare_seconds_ours_f64},
#ifdef DROPCHECK_HAVE_BULLET
    {"bullet", bare_seconds_bullet},
#endif
#ifdef DROPCHECK_HAVE_ODE
    {"ode", bare_seconds_ode},
#endif
#ifdef DROPCHECK_HAVE_BOX2D
    {"box2d", bare_seconds_box2d},
#endif
#ifdef DROPCHECK_HAVE_MUJOCO
    {"mujoco", bare_seconds_mujoco},
#endif
#ifdef DROPCHECK_HAVE_CHIPMUNK
    {"chipmunk", bare_seconds_chipmunk},
#endif
#ifdef DROPCHECK_HAVE_SIMBODY
    {"simbody", bare_seconds_simbody},
    {"simbody-rkm", bare_seconds_simbody_rkm},
#endif
#ifdef DROPCHECK_HAVE_DART
    {"dart", bare_seconds_dart},
#endif
#ifdef DROPCHECK_HAVE_WILDMAGIC
    {"wildmagic", bare_seconds_wildmagic},
#endif
};

}  // namespace

double bare_step_loop(const std::string& engine, const Scene& scene, double h) {
  for (const auto& [name, loop] : kBareLoops)
    if (engine == name) return loop(scene, h);
  throw std::invalid_argument("bare_step_loop: engine '" + engine + "' is not compiled in");
}

}  // namespace dropcheck
