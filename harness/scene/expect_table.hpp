// The [expect] table of a scene file and the description that quotes it (docs/design.md,
// "Scenario files"). A scene states its figures as data, and its description quotes them:
//
//   description = "... stops it at step {law_stop_step} after {law_stop_distance} m ..."
//   [expect]
//   law_stop_step = 62
//   law_stop_distance = 2.509472
//   [expect.medium]                   # one body's figures, quoted as {medium.stack_rest_height}
//   stack_rest_height = 0.75
//
// The loader puts each figure's text, exactly as the file writes it ("2.5510", "1e-5"), where the
// description names it, so the description reads as if the figures were typed into it;
// tests/scenarios/expectations_test.cpp checks every figure against what the harness computes.
#pragma once

#include <cstddef>
#include <string>

#include "harness/core/scene.hpp"
#include "harness/scene/toml_reader.hpp"

namespace dropcheck {

// Most figures one [expect] table holds, its body tables' included.
inline constexpr std::size_t kMaxExpectedFigures = 64;

// Reads the [expect] table of `top` (the scene file's root; none: no figures) into scene.expect and
// replaces every {name} of scene.description by that figure's text. `text` is the file's text, in
// which toml++'s source positions find each figure's text as written. Needs scene.bodies loaded.
// Throws InputError naming the file, line, key and problem for: [expect] not a table; a name not
// [a-z][a-z0-9_]*; a table in [expect] that names no body; a figure that is not a finite number,
// or is not written as a plain decimal (62, 2.5510, -0.015, 1e-5); more than kMaxExpectedFigures
// figures; a '{' never closed or a '}' that closes none; a {name} that names no figure; and a
// figure the description never quotes.
void load_expect(const Reader& top, const std::string& text, Scene& scene);

}  // namespace dropcheck
