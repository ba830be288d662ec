// The edge landing of tests/ours/collision_test.cpp, shared with the turned-contact oracle's test:
// a unit cube of 1 kg turned by 30 degrees about z, its lowest edge 1e-4 m into a floor whose top
// is at y = 0, falling at 1 m/s, frictionless, e = 0, at h = 1/60. Its closed form is written
// there.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace dropcheck::testing {

struct EdgeLanding {
  double theta = std::numbers::pi / 6;
  double depth = 1e-4;  // m
  double v0 = -1.0;     // m/s
  double h = 1.0 / 60.0;
  double g = 9.8;

  Eigen::Quaterniond rotation() const {
    return Eigen::Quaterniond(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()));
  }
  // The lowest edge's midpoint from the centre: the corners (-0.5, -0.5, +-0.5) turned.
  Eigen::Vector3d arm() const { return rotation() * Eigen::Vector3d(-0.5, -0.5, 0.0); }
  Eigen::Vector3d centre() const { return {0.0, -arm().y() - depth, 0.0}; }
  double un() const { return v0 - g * h; }
  double vy() const { return un() * 6 * arm().x() * arm().x() / (1 + 6 * arm().x() * arm().x()); }
  double wz() const { return -6 * arm().x() * un() / (1 + 6 * arm().x() * arm().x()); }
};

}  // namespace dropcheck::testing
