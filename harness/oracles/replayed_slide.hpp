// A slide as an engine's own contact solver makes it, where the harness replays that solver
// (harness/core/contact_solver.hpp): the member a slide on that engine is judged against, beside
// the ideal clamp law of contact_laws.hpp whose difference the replay explains.
#pragma once

#include <cstdint>

#include "harness/core/contact_solver.hpp"
#include "harness/core/scene.hpp"
#include "harness/oracles/contact_laws.hpp"

namespace dropcheck {

// True for a solver the harness replays (every kind but exact).
bool replayed(const ContactSolver& solver);

// The path of `setup`'s slide after steps 0..steps at step h under `solver`, read as
// observed_slide_path reads a run. Throws std::invalid_argument for an exact solver or a scene
// outside the replay's scope (harness/oracles/box2d_step.hpp: one dynamic box on one static box).
SlidePath replayed_slide_path(const Scene& scene, const SlideSetup& setup,
                              const ContactSolver& solver, double h, std::int64_t steps);

}  // namespace dropcheck
