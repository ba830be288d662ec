// The contact part of a scene's section of the report (report_contact.cpp): a slide to a stop
// against its friction model's clamp law, a bounce against its bounce law, each with the closed
// form (docs/contact.md).
#pragma once

#include <string>

#include "harness/measure/evaluate.hpp"

namespace dropcheck {

// The slide table at the default step ("" when the scene has no slide).
std::string slide_section(const SceneEvaluation& se);

// True when the engine's default-step run departs from its friction model's clamp law on a slide
// that law answers exactly (as `dropcheck check` judges it).
bool off_slide_law(const SceneEvaluation& se, const EngineEvaluation& ev);

// The bounce table at the default step ("" when the scene has no bouncing sphere).
std::string bounce_section(const SceneEvaluation& se);

// True when the engine's default-step run departs from its bounce law (as `dropcheck check`
// judges it).
bool off_bounce_law(const SceneEvaluation& se, const EngineEvaluation& ev);

// The stack table at the default step ("" when the scene has no resting stack).
std::string stack_section(const SceneEvaluation& se);

// True when a body of the engine's default-step run leaves its stack law's bounds without the
// named limit of an iterative solver (as `dropcheck check` judges it).
bool off_stack_law(const SceneEvaluation& se, const EngineEvaluation& ev);

}  // namespace dropcheck
