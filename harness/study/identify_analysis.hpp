// What `dropcheck identify` measures and concludes, before a word is written: the law behind a
// free-flight run (harness/oracles/identify.hpp, identify_rotation.hpp) with the engine's order
// against the closed form (closed_form_order.hpp), an error-controlled engine's error per accuracy
// (accuracy_response.hpp), an engine's friction model and combine rule from its slides
// (harness/oracles/identify_friction.hpp), each against what the engine declares.
// harness/cli/cmd_identify.cpp chooses the engine and the step and prints these structs.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "harness/core/engine.hpp"
#include "harness/core/trajectory.hpp"
#include "harness/oracles/identify.hpp"
#include "harness/oracles/identify_friction.hpp"
#include "harness/oracles/identify_rotation.hpp"
#include "harness/study/accuracy_response.hpp"
#include "harness/study/closed_form_order.hpp"

namespace dropcheck {

// A run that did not finish: identify reports it instead of a fit.
struct RunFailure {
  std::string engine;
  std::int64_t step = 0;
  RunStatus status = RunStatus::ok;
  std::string failure;
};

// The failure of `run` (named for `engine`), or nullopt when it finished.
std::optional<RunFailure> run_failure(const Trajectory& run, const std::string& engine);

// What the engine declares against what was found.
enum class DeclaredMatch {
  matches,   // the member found is the declared one
  tied,      // the declared member is one of equal fits: not confirmed
  mismatch,  // another member was found, or none
};

// The declared rotational member (and its damping placement) against the fits.
struct RotationDeclared {
  RotationFit member;  // the declared member (its fit figures unused)
  DeclaredMatch match = DeclaredMatch::mismatch;
};

// The law behind a free-flight run.
struct FreeFlightIdentity {
  std::string scene;
  std::string engine;  // the run's
  std::size_t bodies = 0;
  std::int64_t steps = 0;
  double h = 0.0;                                     // s
  Identification law;                                 // every member's fit, and which one is named
  std::optional<Law> declared;                        // with an engine: its declared law ...
  DeclaredMatch law_match = DeclaredMatch::mismatch;  // ... against the member found
  std::optional<ClosedFormOrder> order;               // with an engine: its order at 2h, h and h/2
  bool order_matches = true;  // every order measured is the declared law's (true when none is)
  std::optional<RotationIdentification> rotation;     // the run rotates: its rotational member
  std::optional<RotationDeclared> rotation_declared;  // ... and, with an engine, the declared one
  bool rotation_unread = false;  // the scene turns but the run carries no rotation columns

  bool named() const;           // one linear member fits, alone
  bool rotation_named() const;  // one rotational member fits, alone
  bool ok() const;  // named, as declared (with an engine), order and rotation as declared
};

// The law behind `run` of `scene`; with `engine` (the one that ran it), against its declaration
// and its order. Throws InputError when the run cannot be identified (identify_law).
FreeFlightIdentity identify_free_flight(const Scene& scene, const Trajectory& run,
                                        Engine* engine = nullptr);

// An engine run on a free-flight scene at step h: an error-controlled engine's error per accuracy;
// else its run's failure, or the law behind its run.
struct EngineIdentity {
  std::string scene;
  EngineInfo info;
  double h = 0.0;                            // s
  std::optional<AccuracyResponse> accuracy;  // error-controlled: no fixed-step member to fit
  std::optional<RunFailure> failed;
  std::optional<FreeFlightIdentity> fit;

  bool ok() const;
};

EngineIdentity identify_engine(const Scene& scene, Engine& engine, double h);

// An engine for identifying friction on a scene, and whether it was given each body's own
// coefficient verbatim (`raw`: its adapter does not map the scene's; its combine rule makes the
// pair's).
struct FrictionEngine {
  std::unique_ptr<Engine> engine;
  bool raw = false;
};

// Where identify gets its engines and steps: the command line's --engine and --dt.
struct IdentifySource {
  // The engine's info as registered, whatever the scene; nullopt when it is not compiled in.
  std::function<std::optional<EngineInfo>()> named_info;
  // The engine for `scene`; throws InputError, with the reason, when none can run it.
  std::function<FrictionEngine(const Scene&)> friction_engine;
  // The step to run `scene` at; throws InputError on a step the scene refuses.
  std::function<double(const Scene&)> step;
};

// An engine's friction model from its slides at 0 and 45 degrees.
struct FrictionModelIdentity {
  std::string scene;
  std::string engine;
  bool planar = false;  // a 2-D engine: one tangent direction, the models coincide; nothing run
  std::optional<RunFailure> failed;     // a slide's run failed
  int still_sliding_angle = -1;         // the slide at this angle (0 or 45) still slides at the end
  double still_sliding_distance = 0.0;  // ... having come this far (m)
  bool raw = false;                     // run with each body's own coefficient: no model declared
  std::optional<double> mu;             // raw: the pair's coefficient the slide shows
  FrictionModel declared = FrictionModel::cone;
  std::optional<FrictionIdentification> found;  // both slides measured: the ratio and the model

  // Raw: a model named. Else the declared model fits (named alone, or among the models this slide
  // cannot tell apart).
  bool ok() const;
};

// The friction model of the engine `source` gives on `scene`, a slide (launched, or pulled along a
// ramp). Throws InputError when the scene's slide cannot be turned (slide_pair) or no engine can
// run it.
FrictionModelIdentity identify_friction_model(const Scene& scene, const IdentifySource& source);

// An engine's rule for combining two bodies' friction coefficients.
struct CombineRuleIdentity {
  std::string engine;
  bool per_pair = false;  // its adapter sets each pair's friction itself: no rule to identify
  std::optional<RunFailure> failed;
  std::optional<CombineIdentification> found;

  bool ok() const;  // not per pair: the run finished and one rule was named
};

// The combine rule of `engine` on the slide of `scene` run with two coefficients (combine_scene).
CombineRuleIdentity identify_combine_rule(const Scene& scene, Engine& engine,
                                          const IdentifySource& source);

}  // namespace dropcheck
