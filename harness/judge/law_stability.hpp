// Whether an engine's own declared law is unstable at a step on a scene, and why: the cause of a
// LIMIT verdict when the engine blows up there (harness/study/checks.hpp).
//
// The law's per-step linear map on a spring and its stability edge are derived once, in
// harness/oracles/stability_theory.cpp (spring_step_stable); this file only names the result.
#pragma once

#include <string>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"
#include "harness/judge/own_law.hpp"

namespace dropcheck {

// "" when every dynamic body's law is stable at h; otherwise one sentence naming the law, the step
// and the first unstable spring, e.g. "its law (semi-implicit Euler, damping after the forces
// (ours, Box2D, MuJoCo)) is unstable at h = 1/25: omega*h = 2.4 > 2 (its edge on this spring) for
// the spring on 'bob'". Free flight is stable at every h under every Euler member; RK4 damps only
// while k*h <= 2.785 (kRk4DampingEdge).
std::string law_instability(const Scene& scene, Law law, const Timestep& h);

// True when `run` stopped by blowing up (NaN/Inf state, engine error, crash), not by a refusal,
// memory or time limit.
bool blew_up(const Trajectory& run);

// `run` against its own law (unstable at the run's step) up to where the run stopped or where the
// law, iterated in the engine's arithmetic, left finite values, whichever comes first: the own-law
// tolerance scales with the largest finite value the law reaches. A blow-up that ended the run is
// not counted (OwnLawVerdict::failure stays empty).
OwnLawVerdict judge_while_law_finite(const EngineInfo& info, const Scene& scene,
                                     const Trajectory& run);

}  // namespace dropcheck
