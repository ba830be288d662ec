#include "harness/oracles/simbody_brick_step.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "harness/core/rotation_law.hpp"

namespace dropcheck {
namespace {

// Simbody's SignificantReal in double, eps^(7/8) (SimTKcommon NTraits.h): a slip below it has no
// direction and gets no friction.
const double kSignificant = std::pow(std::numeric_limits<double>::epsilon(), 0.875);

}  // namespace

Wrench brick_half_space(const SimbodyContact& c, const Vec3& half_extents, const Vec3& position,
                        const Quat& orientation, const Vec3& velocity, const Vec3& angular_velocity,
                        const Vec3& normal, const Vec3& top) {
  const Eigen::Matrix3d R = orientation.toRotationMatrix();
  // The face most nearly facing -n: axis k, side s (its outward normal s*R_k).
  const Eigen::Vector3d along = R.transpose() * normal;
  int k = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(along[a]) > std::abs(along[k])) k = a;
  const double side = along[k] > 0.0 ? -1.0 : 1.0;
  const int a1 = (k + 1) % 3, a2 = (k + 2) % 3;
  Wrench out;
  for (const double s1 : {-1.0, 1.0})
    for (const double s2 : {-1.0, 1.0}) {
      Vec3 local;
      local[k] = side * half_extents[k];
      local[a1] = s1 * half_extents[a1];
      local[a2] = s2 * half_extents[a2];
      const Vec3 vertex = position + R * local;
      const double depth = normal.dot(top - vertex);
      if (depth <= 0.0) continue;
      const Vec3 point = vertex + (0.5 * depth) * normal;
      const Vec3 arm = point - position;
      const Vec3 u = velocity + angular_velocity.cross(arm);
      const double rate = -u.dot(normal);
      const double f = brick_vertex_force(c, depth, rate);
      if (f <= 0.0) continue;
      Vec3 force = f * normal;
      const Vec3 slip = u + rate * normal;
      if (const double s = slip.norm(); s > kSignificant) {
        const double mu = stribeck(c.friction, c.friction, s / c.transition_velocity);
        force -= (f * mu / s) * slip;
      }
      out.force += force;
      out.moment += arm.cross(force);
    }
  return out;
}

std::vector<BodyState> simbody_brick_states(const Scene& scene, std::size_t body, double h,
                                            std::int64_t steps, std::vector<RotationState>* turns) {
  const Body& b = scene.bodies[body];
  if (b.shape != Shape::box || b.is_static || pushed(scene, body))
    throw std::invalid_argument(
        "Simbody's brick contact is predicted for a dynamic box that nothing but gravity, its "
        "damping and its floor act on");
  const SimbodyContact c = simbody_contact(scene, h);
  const double m = b.mass;
  const Vec3 I = inertia_of(b);
  const Vec3 n(0.0, 1.0, 0.0);
  const double linear_damper = m * -std::expm1(-scene.world.damping_rate * h) / h;
  const Vec3 angular_damper = I * (-std::expm1(-scene.world.angular_damping_rate * h) / h);
  Spin<double> spin;
  spin.q = b.orientation;
  spin.w = b.angular_velocity;
  Vec3 x = b.position, v = b.velocity;
  std::vector<BodyState> out{{x, v}};
  if (turns) *turns = {{spin.q, spin.w}};
  const Law linear{DampingOrder::BeforeForces, PositionUpdate::SemiImplicit};
  for (std::int64_t step = 1; step <= steps; ++step) {
    Wrench contact;
    for (const Body& floor : scene.bodies)
      if (floor.is_static && floor.shape == Shape::box) {
        const Wrench w = brick_half_space(c, b.half_extents, x, spin.q, v, spin.w, n,
                                          floor.position + Vec3(0.0, floor.half_extents.y(), 0.0));
        contact.force += w.force;
        contact.moment += w.moment;
      }
    v += h * (scene.world.gravity + (contact.force - linear_damper * v) / m);
    const Vec3 torque = contact.moment - angular_damper.cwiseProduct(spin.w);
    advance_rotation<double>({Gyroscopic::explicit_term, OrientationUpdate::first_order}, linear,
                             1.0, h, I, torque, spin);
    x += h * v;
    out.push_back({x, v});
    if (turns) turns->push_back({spin.q, spin.w});
  }
  return out;
}

}  // namespace dropcheck
