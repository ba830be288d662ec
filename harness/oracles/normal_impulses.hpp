// A landing's normal impulses read from its momentum, and the contact conditions checked on them
// (ContactBench's criteria, on a shipping engine's run): for one body falling straight onto a level
// static floor, with only gravity (g downward) and the contact acting on it, the contact's impulse
// over step n is m*(v_n - v_(n-1) + g*h) along the vertical: the normal impulse N. Beside the
// body's gap to the floor after each step that shows:
//   Signorini           N >= 0: a contact pushes, never pulls;
//   complementarity     N > 0 only in contact: the largest gap at which a step still pushed (a
//                       speculative contact pushes from a distance by design: Bullet's);
//   penetration         the deepest overlap;
//   restitution         each impact's rebound over its approach (at most e; more is energy made).
// No engine has to expose its impulses for this (docs/contact.md "Contact from the momentum").
#pragma once

#include <cstdint>
#include <span>

#include "harness/core/trajectory.hpp"

namespace dropcheck {

struct NormalCertificate {
  int contact_steps = 0;        // steps whose N is above rounding
  std::int64_t pull_step = -1;  // first step with N below -rounding (-1: none)
  double worst_pull = 0.0;      // its most negative N over m*g*h
  double widest_gap = 0.0;      // m: the largest gap after a step whose N pushed
  std::int64_t widest_gap_step = -1;
  double deepest = 0.0;  // m: the deepest overlap after any step (>= 0)
  std::int64_t deepest_step = -1;
  double rebound = 0.0;            // the largest impact's rebound speed over its approach speed
  std::int64_t rebound_step = -1;  // the step that impact began
};

// `states`: the body after each step; `bottom_offset`: from its centre to its lowest point (a
// box's half height, a sphere's radius); `floor_top`: the floor's top; gravity g straight down. An
// impact is a run of pushing steps; its approach is the speed the body would have reached without
// the contact in the first of them, its rebound the largest upward speed during them. Impacts
// slower than `min_approach` (m/s: a body settling) are not counted for the rebound. A step's
// gap is the smaller of the gaps before and after it (a contact found at the step's start pushes
// the body clear by its end). `epsilon`: the engine's arithmetic (2.2e-16 double, 1.2e-7 float):
// an N within 16 epsilon of the speeds it is made from is rounding, neither a push nor a pull.
NormalCertificate normal_certificate(std::span<const BodyState> states, double bottom_offset,
                                     double floor_top, double g, double h, double epsilon,
                                     double min_approach = 0.1);

}  // namespace dropcheck
