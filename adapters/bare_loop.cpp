#include <stdexcept>

#include "adapters.hpp"

namespace dropcheck {

double bare_step_loop(const std::string& engine, const Scene& scene, double h) {
  if (engine == "ours") return bare_seconds_ours_f32(scene, h);
  if (engine == "ours-f64") return bare_seconds_ours_f64(scene, h);
#ifdef DROPCHECK_HAVE_BULLET
  if (engine == "bullet") return bare_seconds_bullet(scene, h);
#endif
#ifdef DROPCHECK_HAVE_ODE
  if (engine == "ode") return bare_seconds_ode(scene, h);
#endif
#ifdef DROPCHECK_HAVE_BOX2D
  if (engine == "box2d") return bare_seconds_box2d(scene, h);
#endif
#ifdef DROPCHECK_HAVE_MUJOCO
  if (engine == "mujoco") return bare_seconds_mujoco(scene, h);
#endif
  throw std::invalid_argument("bare_step_loop: engine '" + engine + "' is not compiled in");
}

}  // namespace dropcheck
