// Tests harness/oracles/free_rotation.cpp, the closed form of torque-free rotation, against an
// independent reference: Euler's equations integrated here by classical Runge-Kutta at h = 1e-4 s
// (global error about 1e-13 rad/s over 10 s), and against the invariants E and |M|.
#include "harness/oracles/free_rotation.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

using namespace dropcheck;

namespace {

// Euler's equations without torque: I1*w1' = (I2 - I3)*w2*w3 and cyclic.
Vec3 euler(const Vec3& I, const Vec3& w) {
  return {(I[1] - I[2]) * w[1] * w[2] / I[0], (I[2] - I[0]) * w[2] * w[0] / I[1],
          (I[0] - I[1]) * w[0] * w[1] / I[2]};
}

// The body-frame angular velocity every `h` up to t_end, by RK4.
std::vector<Vec3> integrate(const Vec3& I, Vec3 w, double t_end, double h = 1e-4) {
  std::vector<Vec3> out{w};
  const int n = static_cast<int>(std::lround(t_end / h));
  for (int i = 0; i < n; ++i) {
    const Vec3 k1 = euler(I, w), k2 = euler(I, w + 0.5 * h * k1), k3 = euler(I, w + 0.5 * h * k2),
               k4 = euler(I, w + h * k3);
    w += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    out.push_back(w);
  }
  return out;
}

// Largest |closed form - RK4| over [0, t_end], sampled every 0.01 s.
double largest_departure(const Vec3& I, const Vec3& w0, double t_end) {
  const double h = 1e-4;
  const std::vector<Vec3> rk = integrate(I, w0, t_end, h);
  const FreeRotation exact(I, w0);
  double worst = 0.0;
  for (std::size_t i = 0; i < rk.size(); i += 100)
    worst = std::max(worst, (exact.omega(static_cast<double>(i) * h) - rk[i]).norm());
  return worst;
}

// The times at which RK4's component `axis` changes sign (linear interpolation between steps).
std::vector<double> sign_changes(const Vec3& I, const Vec3& w0, double t_end, int axis) {
  const double h = 4e-4;  // RK4's error, about 3e-11 rad/s here, is far below the 1e-6 s compared
  const std::vector<Vec3> rk = integrate(I, w0, t_end, h);
  std::vector<double> out;
  for (std::size_t i = 1; i < rk.size(); ++i) {
    const double a = rk[i - 1][axis], b = rk[i][axis];
    if ((a < 0.0) != (b < 0.0) && a != 0.0)
      out.push_back(h * (static_cast<double>(i - 1) + a / (a - b)));
  }
  return out;
}

}  // namespace

TEST_CASE("torque-free rotation matches Euler's equations integrated by RK4, every regime",
          "[oracle][rotation]") {
  const Vec3 I(1.0, 2.0, 3.0);
  // About the axis of largest moment (M^2 > 2*E*I2), both signs of w3; about the axis of least
  // moment (M^2 < 2*E*I2); near the intermediate axis (tumbling); axes given in another order.
  for (const Vec3& w0 : {Vec3(0.2, 0.5, 3.0), Vec3(0.2, 0.5, -3.0), Vec3(3.0, 0.5, 0.2),
                         Vec3(-3.0, -0.5, 0.2), Vec3(0.01, 1.0, 0.01), Vec3(0.05, -2.0, -0.03)}) {
    INFO("w0 = " << w0.transpose());
    CHECK(largest_departure(I, w0, 10.0) < 1e-9);  // measured 5.5e-14 .. 3.9e-11 rad/s
  }
}

TEST_CASE("torque-free rotation is right whatever order the axes are given in",
          "[oracle][rotation]") {
  // Every permutation of the moments, even and odd (an odd one reverses Euler's equations in the
  // formula's frame), in both regimes.
  const double moments[3] = {1.0, 2.0, 3.0};
  int perm[3] = {0, 1, 2};
  do {
    const Vec3 I(moments[perm[0]], moments[perm[1]], moments[perm[2]]);
    for (const Vec3& w0 : {Vec3(0.5, 0.2, 2.0), Vec3(2.0, -0.3, 0.4), Vec3(0.02, 0.03, 1.5)}) {
      INFO("I = " << I.transpose() << ", w0 = " << w0.transpose());
      CHECK(largest_departure(I, w0, 4.0) < 1e-9);
    }
  } while (std::next_permutation(perm, perm + 3));
}

TEST_CASE("Gazebo's tumbling box (10 kg, 0.1 x 0.4 x 0.9 m) matches RK4 and keeps E and |M|",
          "[oracle][rotation]") {
  const double m = 10.0, a = 0.1, b = 0.4, c = 0.9;
  const Vec3 I(m / 12.0 * (b * b + c * c), m / 12.0 * (a * a + c * c), m / 12.0 * (a * a + b * b));
  const Vec3 w0(0.1, 5.0, 0.1);                  // mostly about the intermediate axis: it flips
  CHECK(largest_departure(I, w0, 10.0) < 1e-8);  // measured 4.8e-10 rad/s
  // Its flips: at 1.166, 4.194 and 7.223 s, every half period of 6.057 s.
  const std::vector<double> flips = FreeRotation(I, w0).flips(10.0);
  REQUIRE(flips.size() == 3);
  CHECK(flips[0] == Approx(1.165960).margin(1e-6));
  CHECK(FreeRotation(I, w0).period() == Approx(6.05684).margin(1e-5));
  const FreeRotation r(I, w0);
  for (double t = 0.0; t <= 10.0; t += 0.37) {
    const Vec3 w = r.omega(t);
    CHECK(0.5 * w.dot(I.cwiseProduct(w)) == Approx(r.energy()).epsilon(1e-12));
    CHECK(I.cwiseProduct(w).norm() == Approx(r.momentum()).epsilon(1e-12));
  }
}

TEST_CASE("the Dzhanibekov flips are the sign changes of the intermediate component",
          "[oracle][rotation]") {
  const Vec3 I(1.0, 2.0, 3.0);
  for (const Vec3& w0 : {Vec3(0.01, 1.0, 0.01), Vec3(-0.02, 1.0, 0.01), Vec3(0.01, -1.0, -0.05)}) {
    INFO("w0 = " << w0.transpose());
    const FreeRotation r(I, w0);
    const std::vector<double> exact = r.flips(40.0);
    const std::vector<double> rk = sign_changes(I, w0, 40.0, 1);
    REQUIRE(exact.size() == rk.size());
    REQUIRE(exact.size() >= 2);
    for (std::size_t i = 0; i < exact.size(); ++i) CHECK(exact[i] == Approx(rk[i]).margin(1e-6));
    // Flips come every half period.
    CHECK(exact[1] - exact[0] == Approx(r.period() / 2.0).epsilon(1e-12));
  }
}

TEST_CASE("the closed form is periodic with period 4K(k)/lambda", "[oracle][rotation]") {
  const FreeRotation r(Vec3(1.0, 2.0, 3.0), Vec3(0.3, 1.2, 0.7));
  const double T = r.period();
  REQUIRE(std::isfinite(T));
  for (double t : {0.0, 0.4, 1.7})
    CHECK((r.omega(t + T) - r.omega(t)).norm() < 1e-12 * r.omega(t).norm() * (1.0 + T));
}

TEST_CASE("axisymmetric bodies precess steadily; a sphere or a principal axis does not move",
          "[oracle][rotation]") {
  // I1 = I2: (w1, w2) turns at W = (I3 - I1)/I1 * w3 about the symmetry axis.
  const Vec3 I(2.0, 2.0, 3.0), w0(1.0, 0.5, 2.0);
  const FreeRotation r(I, w0);
  const double W = (3.0 - 2.0) / 2.0 * 2.0;
  for (double t : {0.0, 0.3, 2.5}) {
    const Vec3 w = r.omega(t);
    CHECK(w[0] == Approx(std::cos(W * t) - 0.5 * std::sin(W * t)));
    CHECK(w[1] == Approx(std::sin(W * t) + 0.5 * std::cos(W * t)));
    CHECK(w[2] == 2.0);
  }
  CHECK(r.period() == Approx(2.0 * M_PI / W));
  CHECK(largest_departure(I, w0, 10.0) < 1e-9);
  CHECK(largest_departure(Vec3(1.0, 2.0, 2.0), Vec3(0.7, 1.0, -0.4), 10.0) < 1e-9);
  CHECK(r.flips(100.0).empty());
  const FreeRotation sphere(Vec3(1.0, 1.0, 1.0), Vec3(1.0, 2.0, 3.0));
  CHECK(sphere.omega(5.0) == Vec3(1.0, 2.0, 3.0));
  CHECK(std::isinf(sphere.period()));
  const FreeRotation axis(Vec3(1.0, 2.0, 3.0), Vec3(0.0, 4.0, 0.0));  // unstable, but exact
  CHECK(axis.omega(5.0) == Vec3(0.0, 4.0, 0.0));
}

TEST_CASE("moments that no body has are refused", "[oracle][rotation]") {
  CHECK_THROWS_AS(FreeRotation(Vec3(1.0, 1.0, 3.0), Vec3(1.0, 0.0, 0.0)), std::invalid_argument);
  CHECK_THROWS_AS(FreeRotation(Vec3(0.0, 1.0, 1.0), Vec3(1.0, 0.0, 0.0)), std::invalid_argument);
  CHECK_THROWS_AS(FreeRotation(Vec3(-1.0, 1.0, 1.0), Vec3(1.0, 0.0, 0.0)), std::invalid_argument);
  CHECK_THROWS_AS(FreeRotation(Vec3(NAN, 1.0, 1.0), Vec3(1.0, 0.0, 0.0)), std::invalid_argument);
}
