// The report's stability section: every engine compiled in on the extreme scenes, as Markdown.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "harness/study/evaluate.hpp"

namespace dropcheck {

// Loads each scene file (InputError for a bad one), studies it on the engines passed in
// (harness/study/stability_study.hpp) and returns a Markdown section: verdicts at each scene's
// step, largest stable step (measured / theory for springs), error against the analytic oracle, and
// a sentence on each failure. Deterministic: fixed formatting, scenes sorted by name, no timings.
// One progress line per scene and engine goes to `progress`.
std::string stability_report_section(const std::vector<std::string>& extreme_scene_files,
                                     const std::vector<EngineSlot>& engines,
                                     std::ostream& progress);

}  // namespace dropcheck
