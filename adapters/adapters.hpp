// Factories of the adapters compiled into this build; only registry.cpp calls them. And each
// engine's bare stepping loop, for the benchmark (bench/) to compare the harness loop against.
#pragma once

#include <memory>
#include <string>

#include "harness/core/engine.hpp"

namespace dropcheck {

std::unique_ptr<Engine> make_ours_f32();
std::unique_ptr<Engine> make_ours_f64();
std::unique_ptr<Engine> make_bullet();       // DROPCHECK_HAVE_BULLET
std::unique_ptr<Engine> make_ode();          // DROPCHECK_HAVE_ODE
std::unique_ptr<Engine> make_box2d();        // DROPCHECK_HAVE_BOX2D
std::unique_ptr<Engine> make_mujoco();       // DROPCHECK_HAVE_MUJOCO
std::unique_ptr<Engine> make_chipmunk();     // DROPCHECK_HAVE_CHIPMUNK
std::unique_ptr<Engine> make_simbody();      // DROPCHECK_HAVE_SIMBODY
std::unique_ptr<Engine> make_simbody_rkm();  // DROPCHECK_HAVE_SIMBODY
std::unique_ptr<Engine> make_dart();         // DROPCHECK_HAVE_DART
std::unique_ptr<Engine> make_wildmagic();    // DROPCHECK_HAVE_WILDMAGIC

// Bare stepping loops: `scene` loaded by the adapter at step h (untimed), then step_count(scene, h)
// calls of the engine's own step function through its own API, with no forces, reads, checks or
// sampling; returns the wall seconds of those calls. Throws EngineError as load() does.
double bare_seconds_ours_f32(const Scene& scene, double h);
double bare_seconds_ours_f64(const Scene& scene, double h);
double bare_seconds_bullet(const Scene& scene, double h);       // DROPCHECK_HAVE_BULLET
double bare_seconds_ode(const Scene& scene, double h);          // DROPCHECK_HAVE_ODE
double bare_seconds_box2d(const Scene& scene, double h);        // DROPCHECK_HAVE_BOX2D
double bare_seconds_mujoco(const Scene& scene, double h);       // DROPCHECK_HAVE_MUJOCO
double bare_seconds_chipmunk(const Scene& scene, double h);     // DROPCHECK_HAVE_CHIPMUNK
double bare_seconds_simbody(const Scene& scene, double h);      // DROPCHECK_HAVE_SIMBODY
double bare_seconds_simbody_rkm(const Scene& scene, double h);  // DROPCHECK_HAVE_SIMBODY
double bare_seconds_dart(const Scene& scene, double h);         // DROPCHECK_HAVE_DART
double bare_seconds_wildmagic(const Scene& scene, double h);    // DROPCHECK_HAVE_WILDMAGIC

// The bare loop of the engine registered as `engine`; throws std::invalid_argument when it is not
// compiled into this build.
double bare_step_loop(const std::string& engine, const Scene& scene, double h);

}  // namespace dropcheck
