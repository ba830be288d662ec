// The seed's fixed-timestep loop (main.odin), as a reusable piece:
//
//   physicsAccumulator += deltaTime
//   for physicsAccumulator >= PHYSICS_TIMESTEP {
//     ApplyPhysics(models, PHYSICS_TIMESTEP)
//     physicsAccumulator -= PHYSICS_TIMESTEP
//   }
//
// Frame times in, whole steps out, the remainder carried to the next frame. The leftover fraction
// alpha = accumulator / step in [0, 1) is what a renderer interpolates with.
//
// The seed runs as many steps as the accumulator holds. After a long hitch (a 0.5 s frame) that is
// 30 steps in one frame, which makes the next frame slower still: the "spiral of death". Here at
// most `maxStepsPerFrame` steps run per frame; the time beyond that is dropped and reported in
// `droppedTime`, never run silently.
#pragma once

#include <cmath>

#include "constants.hpp"

namespace ours {

// Default cap: 8 steps (0.133 s of simulation at 60 Hz) per rendered frame.
inline constexpr int MAX_STEPS_PER_FRAME = 8;

template <typename T>
struct FrameSteps {
  int steps = 0;         // whole physics steps to run this frame
  T droppedTime = T(0);  // seconds discarded by the cap (0 unless the frame hitched)
  T alpha = T(0);        // leftover fraction of a step, for render interpolation
};

template <typename T>
struct PhysicsAccumulator {
  T timestep = PHYSICS_TIMESTEP<T>;
  int maxStepsPerFrame = MAX_STEPS_PER_FRAME;
  T physicsAccumulator = T(0);

  // Adds one frame's time and returns how many fixed steps to run now.
  FrameSteps<T> Advance(T deltaTime) {
    FrameSteps<T> out;
    physicsAccumulator += deltaTime;
    while (physicsAccumulator >= timestep && out.steps < maxStepsPerFrame) {
      physicsAccumulator -= timestep;
      ++out.steps;
    }
    if (physicsAccumulator >= timestep) {  // capped: keep the fraction, drop whole steps
      // fmod is exact (acc - q*timestep for a whole q, in [0, timestep)) and needs no integer
      // step count, which would overflow an int after a hitch of more than 2^31 steps.
      const T fraction = std::fmod(physicsAccumulator, timestep);
      out.droppedTime = physicsAccumulator - fraction;
      physicsAccumulator = fraction;
    }
    out.alpha = physicsAccumulator / timestep;
    return out;
  }
};

}  // namespace ours
