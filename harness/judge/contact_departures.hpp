// Where a run leaves its engine's contact laws (docs/contact.md): each slide off its friction
// model's clamp law, each bounce off its bounce law, each stacked body off its stack law, a
// tumbling landing off its turned-box contact law. One place for the report's flags and the
// stability classifier.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "harness/core/engine.hpp"
#include "harness/core/scene.hpp"
#include "harness/core/trajectory.hpp"

namespace dropcheck {

enum class ContactLaw { slide, bounce, stack, turned };

struct ContactDeparture {
  ContactLaw law = ContactLaw::slide;
  std::size_t body = 0;
  std::int64_t step = 0;  // where it showed: the slide's stop (or the run's end), the bounce's
                          // first step off its law, the run's end for a stack, a tumbling landing's
                          // first step off its law
  std::string what;       // the verdict's sentence
};

// The departures of `run` (at step h, every step kept) from the contact laws of `info`. A slide the
// engine's model has no exact answer for, and a stack its solver is not expected to hold (a named
// limit), are not departures.
std::vector<ContactDeparture> contact_departures(const Scene& scene, const Trajectory& run,
                                                 const EngineInfo& info, double h);

}  // namespace dropcheck
