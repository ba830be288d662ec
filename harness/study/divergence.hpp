// What the cross-engine check measures over a scene's sweep (check_divergence,
// harness/study/checks.hpp), before a word is written: at each step, what was compared and what
// explains the difference; then the order observed, and, out of band, the extended sweep and the
// phase drift. checks.cpp writes the check's message from this struct alone.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/timestep.hpp"
#include "harness/judge/attribution.hpp"
#include "harness/judge/own_law.hpp"
#include "harness/judge/tolerances.hpp"
#include "harness/study/phase_drift.hpp"
#include "harness/study/sweep.hpp"

namespace dropcheck {

// One step of the scene's sweep.
struct DivergenceStep {
  Timestep h;
  // Either law is unstable at h: the step measures the blow-up, not the order, and is left out.
  std::string unstable_engine;  // whose law (the engine's is asked first)
  std::string unstable;         // why (law_instability)
  std::string failure;          // the engine's run at h failed: the sweep stops here
  // The error the order is taken of (m): the reference's against the closed form; another
  // engine's law part |L_E - L_R| when the laws differ beyond rounding, else 0.
  double error = 0.0;
  // The reference (convergence to analytic): its run against its own law, and that law's position
  // tolerance in its arithmetic (m).
  std::optional<OwnLawVerdict> own;
  double own_tolerance = 0.0;
  // Another engine: why its run and the reference's differ (harness/judge/attribution.hpp).
  std::optional<Attribution> attribution;

  // The step ran and was measured (neither left out nor failed).
  bool measured() const;
};

// What decided the check, in the order the check asks.
enum class DivergenceFinding {
  no_closed_form,  // the reference on a scene with no analytic solution: nothing to converge to
  run_failed,      // the engine's run failed at the last step
  unexplained,     // at the last step an engine departs from its own law (the attribution says who)
  no_order,        // fewer than two steps where both laws are stable
  same_law,        // another engine whose law part is within rounding at the finest step
  order,           // the order over the scene's sweep: in band, or at rounding level
  not_extended,    // out of band, and the reference departs from its own law at a step
  extended,        // out of band while both follow their laws: the sweep was extended
  phase_drift,     // the reference's extension stopped short; its law's phase drift was judged
};

struct Divergence {
  std::string engine, reference;
  bool to_analytic = false;    // the engine is the reference: its convergence to the closed form
  std::string no_closed_form;  // why the scene has no analytic solution (analytic_unavailable)
  std::vector<DivergenceStep> steps;  // the scene's sweep, largest first, up to where it stopped
  double noise = 0.0;      // errors at or below it are rounding: kOrderMeasurableFactor times the
                           // reference's largest own-law tolerance (0 for another engine)
  double precision = 0.0;  // the reference's largest precision part (own_law.hpp), extension's too
  std::optional<OrderEstimate> order;     // over the measured steps of the scene's sweep
  std::string pre_asymptotic;             // when extended: why the steps may be pre-asymptotic
  std::optional<ExtendedSweep> extended;  // the sweep with halvings of its finest step added
  std::optional<DriftVerdict> drift;      // the reference's extension stopped short: the drift
  DivergenceFinding finding = DivergenceFinding::order;
  bool passed = false;

  // The measured steps' sizes (s) and errors (m), the order's inputs.
  std::vector<double> measured_h() const;
  std::vector<double> measured_errors() const;
  // The first step left out, and the first the reference departs from its own law at; or null.
  const DivergenceStep* first_left_out() const;
  const DivergenceStep* first_departure() const;
  // The first step whose two runs' rotations are apart: the rotational laws differ, or one law
  // leaves them apart by rounding. Null when none is (or the runs do not rotate).
  const DivergenceStep* rotations_apart() const;
  // A LIMIT: the phase drift of the reference's law explains every error of its sweep.
  bool limit() const;
};

// Runs the scene's sweep on the engine and on `reference` (the same engine: its convergence to the
// closed form) and decides as check_divergence documents; at most `extension_steps` steps added.
Divergence measure_divergence(const Scene& scene, const EngineFactory& make,
                              const EngineFactory& reference,
                              std::int64_t extension_steps = tolerance::kExtensionSteps);

}  // namespace dropcheck
