// A stability study out (stability_io.cpp): JSON for scripts (exact numbers) and a plain-text
// table for people.
#pragma once

#include <string>

#include "harness/study/stability_search.hpp"
#include "harness/study/stability_study.hpp"

namespace dropcheck {

// The study as JSON: {"scene", "file", "dt", ..., "engines": [{"engine", "status", "failures",
// "max_stable_dt", ...}]}; numbers exact (%.17g), NaN as null.
std::string stability_to_json(const SceneStability& study, const SearchOptions& search);

// One line on a step search: "fails at 0.0333481 s (unbounded growth)", "no failure up to the cap
// 0.25 s", "frozen below 8e-05 s; ...".
std::string search_summary(const StepSearch& search);

// The study as a plain-text table plus one sentence per failure, for the terminal.
std::string stability_to_text(const SceneStability& study);

}  // namespace dropcheck
