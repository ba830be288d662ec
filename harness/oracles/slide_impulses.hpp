// A slide's contact impulses read from its momentum, and Coulomb's law checked on them: for one
// body on a level static floor with only gravity and the contact acting on it, the contact's
// impulse over step n is the part of the velocity change that gravity does not explain,
// J = m*(v_n - v_(n-1) - g*h). Its part along the floor's normal (+y) is the normal impulse N, the
// rest the friction F. No engine has to expose its impulses and no solver is modelled: this is
// the law checked on what the run did (docs/contact.md "Coulomb's law from the momentum").
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "harness/core/trajectory.hpp"
#include "harness/oracles/contact_laws.hpp"

namespace dropcheck {

// One step's impulses per unit mass (m/s).
struct SlideImpulse {
  double normal = 0.0;  // N/m along +y
  double along = 0.0;   // F/m along the slip friction must cancel (negative: against it)
  double across = 0.0;  // |F/m| across it
  double needed = 0.0;  // the step-start slip plus the pull's h*pull: what friction must cancel
  double slip = 0.0;    // the speed along the floor at the step's end
  double speeds = 0.0;  // |v| at the step's start and end, summed: the scale of its rounding
};

// Entry n - 1 holds step n, for n = 1 .. states.size() - 1 (`states`: the slide's body after each
// step, as Trajectory::at gives them).
std::vector<SlideImpulse> slide_impulses(std::span<const BodyState> states, const SlideSetup& s,
                                         double h);

// What Coulomb's law says of each step, given its own normal impulse N: a step whose slip needs
// more than mu*N to cancel (|needed| > mu*N) slips, and its friction must be mu*N against the slip;
// any other step sticks, with |F| <= mu*N and no slip left. Steps are numbered from 1.
struct CoulombCertificate {
  int slipping = 0;          // steps the law says slip
  int exact = 0;             // of them, friction mu*N against the slip to kCoulombRounding
  int stale = 0;             // steps whose friction exceeds mu*N
  int held = 0;              // steps the law says stick
  double worst_short = 0.0;  // largest 1 - F_along/(mu*N) over slipping steps
  std::int64_t worst_short_step = -1;
  double worst_over = 0.0;  // largest |F|/(mu*N) - 1 over every step
  std::int64_t worst_over_step = -1;
  double creep = 0.0;  // largest slip left after a step that sticks (m/s)
  std::int64_t creep_step = -1;
  double min_normal = 0.0, max_normal = 0.0;  // N over m*g*h, the smallest and largest
  // Over the slipping steps: the friction along the slip summed, over mu times their normal
  // impulses summed (1 for Coulomb's law: how far the whole slide's friction is from it), and the
  // median step's friction along the slip over its mu*N (what a coefficient 2 % off moves to
  // 0.98 or 1.02).
  double mean_ratio = 1.0;
  double median_ratio = 1.0;
  std::int64_t pull_step = -1;  // first step with N < 0 (a contact that pulls), -1: none
  // First step outside the bounds (for a mean off its bound, the first slipping step), -1: none.
  std::int64_t first_bad = -1;
  bool holds = false;
};

// The clamp law with the run's own normal impulses: each step's grip is mu*N of that step (the
// step's v_free = v + pull*h is cancelled if |v_free| <= mu*N, else mu*N is taken off it), x +=
// h*v. What Coulomb's law makes of the run's normal impulses, however its solver came to them.
SlidePath coulomb_path(std::span<const SlideImpulse> steps, const SlideSetup& s, double mu,
                       double h);

// The relative bound a step's friction keeps to mu*N: rounding in double.
inline constexpr double kCoulombRounding = 1e-9;

// Checks every step. With median_bound 0 (a solver that solves each step exactly) every step must
// hold to kCoulombRounding. Otherwise (an iterative solver whose single steps stray: a rocking box
// spreads its contacts' slip directions, a contact that lost its normal impulse keeps friction)
// single steps are only reported, and the median slipping step must keep
// |median_ratio - 1| <= median_bound: a coefficient or combine rule 2 % off moves every step, and
// the median with them. A contact that pulls fails either way. `epsilon`: the engine's arithmetic
// (2.2e-16 double, 1.2e-7 float); a float engine's steps are held to 16 epsilon of their speeds.
CoulombCertificate coulomb_certificate(std::span<const SlideImpulse> steps, double mu, double g,
                                       double h, double median_bound, double epsilon = 2.2e-16);

}  // namespace dropcheck
