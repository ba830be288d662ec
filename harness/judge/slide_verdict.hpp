// A slide judged (harness/oracles/contact_laws.hpp): one run against its engine's own law, step by
// step, computed in one place for `check` and `report`. The law is the ideal clamp law of the
// engine's friction model for an exact solver, and the replay of its own solver for one the
// harness replays (harness/oracles/replayed_contact.hpp), with the clamp law beside it and the
// replay at more iterations to show what the iterations leave.
#pragma once

#include <optional>
#include <string>

#include "harness/core/engine.hpp"
#include "harness/core/friction_model.hpp"
#include "harness/oracles/contact_laws.hpp"
#include "harness/oracles/slide_impulses.hpp"

namespace dropcheck {

// The launch speed's relative change, in machine epsilons, that measures a replayed law's own
// sensitivity (4 ulps of a speed of 2 m/s).
inline constexpr double kSensitivityUlps = 4.0;

struct SlideVerdict {
  SlideObservation seen;
  FrictionModel model = FrictionModel::cone;  // the engine's declared model
  RelativeCfm soft;  // its contact's relative constraint force mixing (none: rigid)
  // Judged: the model's slide has an exact answer at this angle (0, 45 degrees) and the run kept
  // every step; not_judged says why not.
  bool exact = false;
  std::string not_judged;
  SlideStop law;              // its clamp law and continuous closed form (when exact)
  SlideObservation law_seen;  // the own law's path (clamp or replay) read as the run's is
  // A replayed solver (ContactSolver): the replay is the own law; the clamp law's path read as the
  // run's, and for an iterative solver the replay at `more_iterations` velocity iterations (4 times
  // the engine's; 0 for a re-solved one).
  std::optional<ContactSolver> solver;
  SlideObservation clamp_seen;
  int more_iterations = 0;
  SlideObservation more_seen;
  double end_continuous = 0.0;  // m along the slip at the run's end, continuous (exact only)
  double off_law = 0.0;         // m: the largest distance between the run and its law over the run
  std::int64_t first_off = -1;  // the first step over tolerance::kSlideDistance from it (-1: none)
  bool follows = false;  // stop step equal and off_law within tolerance::kSlideDistance, or else
                         // off_steps within it
  // When the path leaves its law's: the largest distance between the run and its law one step
  // ahead of the run's own state (slide_steps). A float engine's path drifts from the law's in
  // double by its rounding while every step follows the law.
  double off_steps = -1.0;       // m (-1: not needed, the path follows)
  double off_steps_speed = 0.0;  // m/s: the same for the speed along the slip
  // The neighbouring member of the slide law the run follows instead, when it departs: another
  // friction model ("the cone's clamp law"), the friction resolved after the position update, the
  // grip of the whole gravity on an incline, an explicit position update; empty if none fits.
  std::optional<FrictionModel> instead_model;  // when that member is another friction model
  std::string instead;
  double instead_off = 0.0;  // m: the run's largest distance from it
  // A solver held to Coulomb's law from the run's momentum (held_by_momentum): the
  // certificate of every step; law_seen is then the clamp law with the run's own normal impulses
  // (coulomb_path) and off_law the run's largest distance from it along the slip.
  std::optional<CoulombCertificate> coulomb;
  // A replayed solver's path the run departs from: how far that law departs from itself when the
  // launch speed moves by kSensitivityUlps epsilons either way (the worse of the two), and the
  // first step it is over tolerance::kSlideDistance from itself (-1: never). A law that amplifies
  // rounding that much (MuJoCo's cube hops off its soft floor, and every landing amplifies) cannot
  // tell a run's rounding from another law past that step.
  double self_off = 0.0;
  std::int64_t self_first = -1;
  bool self_measured = false;  // false for a slide not launched (its speed starts at 0)
  // Departs by at most 10 times what its law departs from itself under that rounding: the run
  // cannot be told from its law at this step, a limit of the law, not a fault of the engine
  // (`check` prints LIMIT with limit_text()).
  bool rounding_limited() const;
  std::string limit_text() const;
  // Not blamed: it follows its law, is not judged (no exact answer), or meets that limit. The one
  // judgement `check`, the report's summary and the stability classifier share.
  bool passes() const { return follows || !exact || rounding_limited(); }
  // When none fits: what the engine printed during the run, and what its adapter says that means
  // (harness/judge/engine_messages.hpp); "" when it printed nothing.
  std::string engine_said;
  // "stops at step 62, 2.509472 m; its box pyramid's clamp law: stops at step 62, 2.509472 m
  // (continuous: 1.0204 s, 2.551 m), 9.1e-12 m off it", with " DEPARTS at step 1 (...): it
  // follows the cone's clamp law instead (to 1e-15 m)" when it does not.
  std::string sentence() const;
};

// Against the clamp law of `model`, the position moved as `position` says, under relative
// constraint force mixing `soft` (none: a rigid contact).
SlideVerdict judge_slide(const Trajectory& run, const SlideSetup& setup, FrictionModel model,
                         double h, PositionUpdate position = PositionUpdate::SemiImplicit,
                         const RelativeCfm& soft = {});

// Against the engine's own law: its friction model's clamp law for an exact solver, the replay of
// its solver (info.contact_solver) otherwise.
SlideVerdict judge_slide(const Trajectory& run, const Scene& scene, const SlideSetup& setup,
                         const EngineInfo& info, double h);

}  // namespace dropcheck
