// A slide to a stop judged (harness/oracles/contact_laws.hpp): one run's stop against the ideal
// clamp law of the engine's friction model, computed in one place for `check` and `report`.
#pragma once

#include <optional>
#include <string>

#include "harness/core/friction_model.hpp"
#include "harness/oracles/contact_laws.hpp"

namespace dropcheck {

struct SlideVerdict {
  SlideObservation seen;
  FrictionModel model = FrictionModel::cone;  // the engine's declared model
  bool exact = false;    // the model's slide has an exact answer at this angle (0, 45 degrees)
  SlideStop law;         // its clamp law and continuous closed form (when exact)
  bool follows = false;  // stop step equal, distance within tolerance::kSlideDistance
  std::optional<FrictionModel> instead;  // another model whose law the run follows, if any
  // "stops at step 62, 2.509472 m; its box pyramid's clamp law: step 62, 2.509472 m (continuous:
  // 1.0204 s, 2.551 m)", with " DEPARTS: it follows the cone's law instead" when it does not.
  std::string sentence() const;
};

SlideVerdict judge_slide(const Trajectory& run, const SlideSetup& setup, FrictionModel model,
                         double h);

}  // namespace dropcheck
