#include "harness/timing/calibration.hpp"

#include <array>
#include <chrono>
#include <vector>

namespace dropcheck {
namespace {

// Where the loop's result goes, so that the compiler cannot drop the work.
volatile double g_calibration_sink = 0.0;

}  // namespace

double time_calibration() {
  constexpr double h = 1.0 / 240.0, drag = 0.999, g = -9.8;
  std::vector<std::array<double, 3>> x(kCalibrationParticles), v(kCalibrationParticles);
  for (int i = 0; i < kCalibrationParticles; ++i) {
    x[i] = {0.01 * i, 10.0, 0.0};
    v[i] = {1.0, 0.0, -0.001 * i};
  }
  const auto start = std::chrono::steady_clock::now();
  for (int s = 0; s < kCalibrationSteps; ++s)
    for (int i = 0; i < kCalibrationParticles; ++i) {
      v[i][1] += g * h;
      for (int k = 0; k < 3; ++k) {
        v[i][k] *= drag;
        x[i][k] += h * v[i][k];
      }
    }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double sum = 0.0;  // every particle's result is used, so none of the work is dead
  for (const auto& p : x) sum += p[0] + p[1] + p[2];
  g_calibration_sink = sum;
  return seconds;
}

}  // namespace dropcheck
