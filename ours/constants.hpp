// The seed's constants (Part III, constants.odin), templated on the scalar like the rest of ours/.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ours {

template <typename T>
using Vector3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using Matrix3 = Eigen::Matrix<T, 3, 3>;
template <typename T>
using Quaternion = Eigen::Quaternion<T>;

// Fixed physics step: 60 updates per second (1.0 / 60.0 = 0.0166 s).
template <typename T>
inline constexpr T PHYSICS_TIMESTEP = T(1.0) / T(60.0);

// Earth's gravity, y up: ~9.8 m/s^2 pulling towards -y.
template <typename T>
inline const Vector3<T> GRAVITY{T(0.0), T(-9.8), T(0.0)};

// Per-step velocity factor: each update keeps 98% of the velocity (cuts 2% off).
template <typename T>
inline constexpr T LINEAR_DRAG = T(0.98);

// The same per-step factor for the angular velocity: the seed announces ANGULAR_DRAG "once we get
// to angular movement" without its value; ours keeps 98% as for the linear drag.
template <typename T>
inline constexpr T ANGULAR_DRAG = T(0.98);

}  // namespace ours
