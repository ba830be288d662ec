#include "harness/oracles/identify_rotation.hpp"

#include <algorithm>

#include "harness/core/input_error.hpp"
#include "harness/oracles/own_rotation.hpp"

namespace dropcheck {

RotationIdentification identify_rotation(const Scene& scene, const Trajectory& run) {
  if (!run.rotates || run.samples() == 0)
    throw InputError("", 0, "trajectory",
                     "carries no rotation (no qw..wz columns): nothing to identify a rotational "
                     "law from");
  RotationIdentification id;
  id.damping_seen = scene.world.angular_damping_rate != 0.0;
  std::vector<Law> orders = {DampingOrder::AfterForces,
                             {DampingOrder::AfterForces, PositionUpdate::Explicit}};
  if (id.damping_seen) {
    orders.clear();  // the Euler members: the rotational family places damping as they do
    for (Law l : kLawFamily)
      if (l.scheme == Scheme::Euler) orders.push_back(l);
  }
  const std::vector<RotationState> start(run.rotations.begin(),
                                         run.rotations.begin() + run.bodies());
  const std::vector<Law> rk4 = {kRungeKutta4};
  for (RotationLaw law : kRotationFamily)
    for (const Law order : law == kRotationRk4 ? rk4 : orders) {
      const RotationResidual r = rotation_residual(
          run, predict_rotation_from(law, order, scene, run.h, run.recorded, start));
      id.fits.push_back({law, order, r.angle, r.w});
    }
  std::vector<std::size_t> order(id.fits.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return id.fits[a].max_angle < id.fits[b].max_angle;
  });
  id.best = order[0];
  id.runner_up = order.size() > 1 ? order[1] : order[0];
  id.fits_any = id.fits[id.best].max_angle <= kIdentifyRotationTolerance;
  id.ambiguous = order.size() > 1 &&
                 id.fits[id.runner_up].max_angle <= 2.0 * id.fits[id.best].max_angle + 1e-12;
  return id;
}

}  // namespace dropcheck
