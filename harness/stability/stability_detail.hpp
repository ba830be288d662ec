// Internals shared by the stability sources (not part of the harness interface).
#pragma once

#include <optional>
#include <string>

#include "harness/core/number_format.hpp"
#include "harness/stability/stability.hpp"

namespace dropcheck::stability_detail {

// The constant part and the springs acting on one body, combined (all forces of the scene):
//   m*x'' = m*accel - stiffness*(x - anchor) - dashpot*x'   (rest_length 0 springs)
struct BodyLaw {
  Vec3 accel = Vec3::Zero();   // g + F/m, m/s^2
  double stiffness = 0.0;      // S, N/m
  Vec3 anchor = Vec3::Zero();  // stiffness-weighted anchor, m
  double dashpot = 0.0;        // C, N*s/m
  bool nonlinear = false;      // a spring with a rest length acts on it
};

// The BodyLaw of body `index`.
BodyLaw body_law(const Scene& scene, std::size_t index);

// Distance between |x| and the next representable number above it in `scalar` (m).
double float_spacing(double x, Scalar scalar);

// Failures of growth: spring energy, free-flight speed, contact-scene energy
// (stability_growth.cpp).
void find_growth(const Scene& scene, const Trajectory& run, const ClassifyOptions& o,
                 std::vector<Failure>& out);

// Failures of motion: tunnelling and frozen coordinates (stability_motion.cpp).
void find_tunnelling(const Scene& scene, const Trajectory& run, std::vector<Failure>& out);
void find_frozen(const Scene& scene, const Trajectory& run, Scalar scalar, const ClassifyOptions& o,
                 std::vector<Failure>& out);

}  // namespace dropcheck::stability_detail
