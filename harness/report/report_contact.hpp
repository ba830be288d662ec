// The contact part of a scene's section of the report for a slide to a stop (report_contact.cpp):
// each engine's stop against its friction model's clamp law and the closed form (docs/contact.md).
#pragma once

#include <string>

#include "harness/measure/evaluate.hpp"

namespace dropcheck {

// The slide table at the default step ("" when the scene has no slide).
std::string slide_section(const SceneEvaluation& se);

// True when the engine's default-step run departs from its friction model's clamp law on a slide
// that law answers exactly (as `dropcheck check` judges it).
bool off_slide_law(const SceneEvaluation& se, const EngineEvaluation& ev);

}  // namespace dropcheck
