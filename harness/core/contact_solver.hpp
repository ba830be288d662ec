// How an engine's contact solver reaches a step's impulses (EngineInfo::contact_solver): the member
// of the contact-law family a slide is judged against (harness/judge/slide_verdict.hpp,
// docs/contact.md "Slides").
//
// exact       every step's contact problem is solved exactly (a pivoting LCP, a closed
//             projection): friction takes min(slip, grip*h) off the slip, the clamp laws of
//             harness/oracles/contact_laws.hpp.
// box2d_2_4   Box2D 2.4's sequential impulses, in its float order (harness/oracles/box2d_step.hpp):
//             per velocity iteration each point's friction, clamped by mu times that point's
//             accumulated normal impulse, then the points' normal impulses as one block; warm
//             started from the last step's impulses; then position iterations that push the
//             overlap out beyond the linear slop. A finite number of iterations leaves part of the
//             slip each step, so a slide runs on past the clamp law's stop: replayed, not bounded.
// chipmunk_7  Chipmunk 7's sequential impulses, in its double order
//             (harness/oracles/chipmunk_step.hpp): the bodies move first, then collide; per
//             iteration each contact's bias impulse (the overlap beyond the collision slop), its
//             normal impulse, then its friction clamped by mu times that normal impulse; cached
//             impulses carried to the next step. Replayed, not bounded.
// mujoco_2_2  MuJoCo 2.2's soft contact (harness/oracles/mujoco_step.hpp): each step one convex
//             problem over the accelerations, each contact four pyramid edges n +- mu*t_i whose
//             cost pulls toward a reference acceleration that removes the overlap over a time
//             constant; its Newton solver converges to the problem's minimum, which the harness
//             re-solves exactly from the same collisions. The softness lets a sliding box lift off
//             its leading edge and a held box creep: re-solved, not bounded.
// bullet_3    Bullet 3's sequential impulses (btSequentialImpulseConstraintSolver): per iteration
//             every contact's normal row, then every contact's friction row along that contact's
//             slip, clamped by mu times its accumulated normal impulse; a friction row is solved
//             only while its normal impulse is positive. Its box-box manifold gains and loses
//             corners as the box rocks, so a slide's normal impulse varies from step to step; the
//             harness does not replay it but holds each step to Coulomb's law with the step's own
//             normal impulse, read from the run's momentum (harness/oracles/slide_impulses.hpp):
//             bounded, not replayed.
// sequential_impulses, soft
//             an external engine's declaration (docs/protocol.md, contact-solver): sequential
//             impulses of its own, or a soft (regularised) contact, which dropcheck neither replays
//             nor re-solves. Held, as Bullet's, to Coulomb's law step by step from the run's
//             momentum, within the median bound the engine declares (0: every slipping step at
//             mu*N to rounding).
// hunt_crossley
//             Simbody's compliant Hunt-Crossley forces (harness/core/simbody_contact.hpp), forces
//             the integrator steps like any other: a sphere's vertical drop, and a box's landing
//             or slide under its brick penalty (harness/oracles/simbody_brick_step.hpp), are
//             predicted by the force law stepped as SemiExplicitEuler does: replayed, not bounded.
#pragma once

#include <string>

namespace dropcheck {

enum class ContactSolverKind {
  exact,
  box2d_2_4,
  chipmunk_7,
  mujoco_2_2,
  bullet_3,
  sequential_impulses,
  soft,
  hunt_crossley
};

struct ContactSolver {
  ContactSolverKind kind = ContactSolverKind::exact;
  int velocity_iterations = 0;  // per step (0: solved or re-solved exactly)
  // bullet_3 and the external kinds: how far the median slipping step's friction may be from mu
  // times its normal impulse (relative; single steps stray further: a rocking box spreads its
  // contacts' slip directions, below mu*N, and a contact that loses its normal impulse mid-step
  // keeps its friction, above), and whether the solver keeps such friction.
  double coulomb_median_bound = 0.0;
  bool keeps_stale_friction = false;
  int position_iterations = 0;  // per step, after the positions are updated (Box2D)
};

// "solved exactly every step", "Box2D 2.4 sequential impulses (8 velocity, 3 position iterations,
// warm started), replayed", "MuJoCo 2.2 soft contact (pyramidal cone, its convex step problem
// re-solved)": the solver and how dropcheck predicts it.
std::string describe(const ContactSolver& solver);

// True for a solver held to Coulomb's law from the run's momentum (bullet_3 and the external
// declarations), not predicted step by step.
bool held_by_momentum(const ContactSolver& solver);

}  // namespace dropcheck
