// The contact part of a scene's section of the report (report_contact.cpp): a slide against its
// friction model's clamp law, a bounce against its bounce law, each with the closed form, and a
// stack against its engine's stack law (docs/contact.md).
#pragma once

#include <string>
#include <vector>

#include "harness/judge/contact_departures.hpp"
#include "harness/study/evaluate.hpp"

namespace dropcheck {

// The slide table at the default step ("" when the scene has no slide).
std::string slide_section(const SceneEvaluation& se);

// The bounce table at the default step ("" when the scene has no bouncing sphere).
std::string bounce_section(const SceneEvaluation& se);

// A body falling onto a level static floor alone, as the momentum table takes it.
struct FallingBody {
  std::size_t body = 0;
  double bottom_offset = 0.0;  // m: centre to lowest point (half height, radius)
  double floor_top = 0.0;      // m
};

// Every engine's contact conditions on those bodies from their momentum at the default step
// (harness/oracles/normal_impulses.hpp): pushes, pulls, the widest gap pushed at, the deepest
// overlap, the largest rebound over its approach, each with its step ("" for no body).
std::string momentum_section(const SceneEvaluation& se, const std::vector<FallingBody>& bodies);

// The stack table at the default step ("" when the scene has no resting stack).
std::string stack_section(const SceneEvaluation& se);

// The contact laws the engine's default-step run leaves, each once (contact_departures, as
// `dropcheck check` judges them): the summary's OFF SLIDE / BOUNCE / STACK LAW flags.
std::vector<ContactLaw> departed_laws(const SceneEvaluation& se, const EngineEvaluation& ev);

}  // namespace dropcheck
