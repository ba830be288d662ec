#include "harness/oracles/replayed_slide.hpp"

#include <stdexcept>
#include <vector>

#include "harness/core/box2d_world.hpp"
#include "harness/oracles/box2d_step.hpp"

namespace dropcheck {

bool replayed(const ContactSolver& solver) {
  return solver.kind != ContactSolverKind::exact;
}

SlidePath replayed_slide_path(const Scene& scene, const SlideSetup& setup,
                              const ContactSolver& solver, double h, std::int64_t steps) {
  if (solver.kind != ContactSolverKind::box2d_2_4)
    throw std::invalid_argument("replayed_slide_path: the solver is not replayed");
  const Box2dWorld world = box2d_world(scene, h);
  const std::vector<Box2dState> states =
      box2d_replay(world.bodies, world.gx, world.gy, static_cast<float>(h),
                   {.velocity_iterations = solver.velocity_iterations,
                    .position_iterations = solver.position_iterations},
                   steps);
  std::vector<BodyState> body;
  const std::size_t n = world.bodies.size();
  for (std::size_t k = setup.body; k < states.size(); k += n) {
    const Box2dState& b = states[k];
    body.push_back({Vec3(b.x, b.y, 0.0), Vec3(b.vx, b.vy, 0.0)});
  }
  return slide_path_of(body, setup);
}

}  // namespace dropcheck
