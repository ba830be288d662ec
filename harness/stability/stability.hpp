// Numerical stability: classify one run as stable or by its failure, search the largest stable step
// per engine by bisection on h, and the theoretical edge of a spring under each damping order.
// Engine-neutral: works on Scene, Trajectory and the engine's declared scalar and law only.
//
// The public story, one header per part:
//   stability_classify.hpp  classify_run: one run is stable or fails (FailureMode, Verdict), from
//                           the detectors in stability_growth.hpp and stability_motion.hpp
//   stability_contact.hpp   classify_engine_run: the same for one engine, with its contact laws
//   stability_theory.hpp    a linear spring's stability edge under each member of the law family
//   stability_search.hpp    the largest stable step of one engine, by bisection on h
//   stability_study.hpp     one scene on a set of engines: verdict, error, searched and theory edge
//   stability_io.hpp, stability_report.hpp   the study out: JSON, table, report section
// Including this header gives the classifier; include the others for their parts.
#pragma once

#include "harness/stability/stability_classify.hpp"
