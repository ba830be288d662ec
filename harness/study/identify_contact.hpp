// `identify` on a bounce, a tumbling landing or a slide: which member of a contact law family an
// engine's run follows, tried against every member this build's adapters declare (a fact each
// adapter states once) and the ideal law, computed here and printed by cmd_identify.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/study/identify_analysis.hpp"

namespace dropcheck {

// One member tried against the run.
struct ContactMemberFit {
  std::string member;                    // the member, described ("restitution of the ...")
  std::vector<std::string> declared_by;  // the engines whose adapters declare it ("ideal": none)
  bool judged = true;                    // the member could be replayed for this engine
  bool follows = false;                  // the run follows it, as `dropcheck check` judges
  std::string detail;                    // the verdict's figures
};

struct ContactLawIdentity {
  std::string scene, engine;
  std::string family;  // "bounce law", "turned-box contact law", "contact solver"
  double h = 0.0;
  std::optional<RunFailure> failed;
  std::vector<ContactMemberFit> fits;  // every member tried, the declared one first (if any)
  std::string declared;                // the engine's own member, described
  bool undeclared = false;  // its adapter declares no member (fits then lists what was tried)
  bool ok() const { return !failed && (undeclared || (!fits.empty() && fits.front().follows)); }
};

// The bounce law `engine`'s run of `scene` (a bounce, bounce_setups) at h follows.
ContactLawIdentity identify_bounce_law(const Scene& scene, Engine& engine, double h);

// The turned-box contact law its run of `scene` (a tumbling landing) at h follows.
ContactLawIdentity identify_turned_contact(const Scene& scene, Engine& engine, double h);

// The contact solver its run of `scene` (a slide, slide_setups) at h follows: its declared solver
// judged as `dropcheck check` judges it, then every solver the harness replays or re-solves that
// an adapter of this build declares (Box2D's and Chipmunk's sequential impulses also at a quarter,
// half, twice and four times their iterations: the members that tell an iteration count), and the
// exact clamp law of the engine's friction model. A member follows when every slide of the scene
// follows it.
ContactLawIdentity identify_contact_solver(const Scene& scene, Engine& engine, double h);

}  // namespace dropcheck
