// Factories of the adapters compiled into this build; only registry.cpp calls them.
#pragma once

#include <memory>

#include "harness/core/engine.hpp"

namespace dropcheck {

std::unique_ptr<Engine> make_ours_f32();
std::unique_ptr<Engine> make_ours_f64();
std::unique_ptr<Engine> make_bullet();  // DROPCHECK_HAVE_BULLET
std::unique_ptr<Engine> make_ode();     // DROPCHECK_HAVE_ODE
std::unique_ptr<Engine> make_box2d();   // DROPCHECK_HAVE_BOX2D
std::unique_ptr<Engine> make_mujoco();  // DROPCHECK_HAVE_MUJOCO

}  // namespace dropcheck
