// The contact laws as members of the stability classifier (stability_contact.cpp): a run that
// leaves its engine's slide, bounce, stack or turned-box law (docs/contact.md) is classified
// off_contact_law, so the step search finds the largest step at which an engine still stops a
// slide as its friction model's clamp law says, bounces as its bounce law says, holds its stacks
// and lands a tumbling box as its turned-box law says.
#pragma once

#include "harness/core/engine.hpp"
#include "harness/core/scene.hpp"
#include "harness/judge/stability_classify.hpp"

namespace dropcheck {

// classify_run for the engine `info` describes, with its resting lift (rest offset and stated
// stillness) in the contact-energy rule, plus an off_contact_law failure for each slide, bounce or
// stack of the scene the run leaves its law on. The contact laws are judged on a run that kept
// every step (as the checks' runs do); a run that kept fewer is classified without them.
Verdict classify_engine_run(const Scene& scene, const Trajectory& run, const EngineInfo& info,
                            const ClassifyOptions& options = {});

}  // namespace dropcheck
