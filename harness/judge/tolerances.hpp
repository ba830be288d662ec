// Every tolerance dropcheck judges with, in one place, each with the measured value it was set
// from (commands in the comments; "measured" figures are GCC 12.2, x86_64, Debian 12 packages).
#pragma once

namespace dropcheck::tolerance {

// --- Own law (oracle 2), harness/judge/own_law.hpp -------------------------------------------
// An engine whose operation order the harness copies (EngineInfo::arithmetic) must match its law
// iterated in its own arithmetic to within this many ulps of the largest |x| or |v| the law
// reaches. Measured: 0 ulps (bit for bit) for ours, ours-f64 and box2d on every shipped scene at
// every step of its sweep, and box2d at 150 m/s, h = 1/120 (tests/adapters/conformance_test.cpp).
// Before, the same runs against the long-double law were 6.45e-5 m off (ours and box2d, f32,
// seed_part3 1/120).
inline constexpr double kCopiedUlps = 4.0;

// An engine whose order is not copied is predicted in long double; each step may round each
// coordinate differently from the law, and a spring feeds those roundings back, so its departure
// may grow by up to this many ulps of the largest |x| or |v| per step (n steps: n * kStepUlps
// ulps). Measured worst (`dropcheck check scenarios/*.toml`): ode 1.23e-13 m on seed_part3 (h =
// 1/120, 360 steps, 12.1 m: 0.13 ulp per step), mujoco 1.07e-14 m; bullet 0 m since its damping
// parameter is copied (DampingForm::per_second_power). On scenarios/extreme/stiff_spring a spring
// feeds the roundings back: 5.7 ulps per step (bullet, ode, mujoco: 4.06e-12 m/s after 286 steps at
// h = 1/32).
inline constexpr double kStepUlps = 16.0;

// A rotational own-law tolerance (ulps per step x steps x the law's amplification) above this
// angle judges nothing: an orientation cannot be off by more than pi, and the members of the family
// sit 1.1e-4 rad apart over Gazebo's tumbling box at h = 1e-3. Beyond it the rotation is reported
// as not judged at that step (a float engine whose order is not copied, on a long tumble: 16.5 rad
// for the C example on gazebo_boxes_complex at h = 1e-3).
inline constexpr double kMaxRotationTolerance = 0.1;  // rad

// --- Contact, harness/oracles/contact_laws.hpp --------------------------------------------------
// A sliding body has stopped once its horizontal speed is at most this: ODE's speed after the
// clamp law's stop step is 2.7e-10 m/s on the straight slide (its solver's residual), 1.8e-2 m/s
// one step before.
inline constexpr double kStoppedSpeed = 1e-6;  // m/s
// How far a slide's distance may be from the clamp law's and still follow it: ODE measures
// 9.1e-12 m on the straight slide (2.5094722222313 against 2.5094722222222).
inline constexpr double kSlideDistance = 1e-6;  // m
// A run whose path leaves its contact law's (slide, bounce) still follows the law when each step,
// taken from the run's own state the step before, lands within the path tolerance and within this
// speed of the law's step: ours in float measures at most 1.2e-07 m and 2.0e-07 m/s on the shipped
// slides and bounces (its float rounding, which the law in double amplifies into a drift over a
// slide, or into a contact decided on the other side of a gap within rounding of 0 in a bounce). A
// held block creeping at 1e-5 m/s is caught.
inline constexpr double kStepSpeed = 2e-6;  // m/s
// How far a bounce's path (the sphere's lowest point, every step) may be from its engine's bounce
// law and still follow it: ODE measures at most 1.0e-9, 2.0e-8 and 7.1e-8 m over the 1, 2 and 3 s
// runs at e = 0.1, 0.5 and 0.9 (its contact CFM of 1e-10 leaves each rebound about 4e-8 m/s
// short); Bullet at most 1.7e-14 m.
inline constexpr double kBouncePath = 1e-6;  // m
// A stacked body sinks between these multiples of its engine's steady-state sink
// (harness/core/stack_law.hpp), give or take the engine's StackLaw::sink_bound: ODE reaches 0.99-
// 1.000 of it at 1/60, MuJoCo 0.84-1.000 (its stacks settle from above: 0.84 for mass_ratio's
// 1000 kg cube after 5 s, 0.87 for stack_rest's medium cube; 1.000 for the light cubes at 1/240).
inline constexpr double kStackSinkLow = 0.8;
inline constexpr double kStackSink = 1.05;

// A tumbling landing (harness/judge/turned_verdict.hpp): each step of a run against its engine's
// turned-box contact law, taken from the run's state the step before. A corner within `decide` of
// the face may be in contact or not in the engine's arithmetic, and both are tried. A step may be
// off by kTurnedStepUlps units in the last place of the engine's scalar, of each quantity's size
// in the law's state: |x| and |v| (at least 1 m, 1 m/s), the step's turn |w|*h (at least 1 rad)
// and |w| (at least 1 rad/s). Measured with tumble_drop, its variants with mu = 0.5, e = 0.4 and
// both, and a cube turned 30 degrees landing on an edge while sliding at 1 m/s (mu = 0.5), each at
// h = 1/30, 1/60, 1/120, 1/240 (ours: `dropcheck check`): ours-f64 worst 2.2e-16 m, 1.4e-15 m/s,
// 4.6e-16 rad, 5.4e-15 rad/s (at most 3 ulps of its size), no corner within 1e-12 m of the face;
// ours (f32) worst 1.2e-7 m, 5.6e-7 m/s, 1.5e-7 rad, 2.9e-6 rad/s (3 ulps of |w| = 8 rad/s), up to
// 28 steps of 720 with a corner within 4e-6 m of the face. At h = 0.2123 s (a stability probe),
// ours (f32) turns by 1.7 rad a step and rounds its orientation 1.4e-6 rad off: 7 ulps of that
// turn.
inline constexpr double kTurnedDecideF64 = 1e-12;  // m
inline constexpr double kTurnedDecideF32 = 4e-6;   // m
inline constexpr double kTurnedStepUlps = 32.0;

// --- Orders of convergence, harness/study/sweep.hpp ------------------------------------------
// A damping-order difference, or semi-implicit Euler against the analytic solution, shrinks at
// first order as h halves. Measured on the shipped scenes, sweep 1/30..1/240: 0.971..1.02.
inline constexpr double kFirstOrderLow = 0.9, kFirstOrderHigh = 1.1;
// RK4 (Wild Magic) against the closed form of free_fall_drag over h = 1/30, 1/60, 1/120 measures
// 4.024 and 4.012 (tests/adapters/wildmagic_test.cpp): the slack of its band around 4.
inline constexpr double kFourthOrderSlack = 0.2;
// Below this order a scheme does not converge to the model at all (inconsistent): drag applied
// twice measures 0.03 on free_fall_drag; every member of the law family measures >= 0.97.
inline constexpr double kConsistentOrder = 0.5;
// An error within this many own-law tolerances of zero has no measurable order (rounding bends the
// curve): the smallest shipped analytic error is 5e-3 m against f32 tolerances of ~1e-5 m.
inline constexpr double kOrderMeasurableFactor = 10.0;
// Two laws "differ" when their trajectories are this many own-law tolerances apart.
inline constexpr double kLawsDifferFactor = 10.0;

// --- Pre-asymptotic sweeps, harness/study/sweep.hpp (extend_sweep) ---------------------------
// A sweep whose order is out of the first-order band while its engine follows its law is extended
// with halvings of its finest step; all the added runs of one sweep may take this many steps in
// all. Measured (release build, `time dropcheck check scenarios/extreme/long_run.toml --engine
// ours-f64`, three runs): 2.55-2.86 s for the whole check, 425 MB peak. long_run is the only
// shipped scene that reaches the cap: it adds one halving (h = 1/480, 1.73e6 steps; that run alone
// takes 0.49 s, `dropcheck run ... --dt 1/480`, then its law in both arithmetics and the closed
// form), and the next (1/960, 3.46e6 more) would pass the cap. stiff_spring's 9 halvings add 1.23e6
// steps (its whole check 0.46-0.55 s). Every other shipped scene adds at most 2 halvings.
inline constexpr long long kExtensionSteps = 4'000'000;
// A product of a rate and the step (k*h, omega*h, gamma*h, the phase drift in rad) above this is
// named as a cause of a pre-asymptotic sweep. Naming only, no verdict depends on it. The products
// named on the shipped scenes (`dropcheck check scenarios/*.toml scenarios/extreme/*.toml`, every
// engine): gamma*h = 0.1 (stiff_spring_drag, the smallest), phase drift 0.218 rad
// (stiff_spring_drag), k*h = 0.333 and 0.5, omega*h = 0.5 and 1, phase drift 0.646 rad (long_run)
// and 6.43 rad (stiff_spring).
inline constexpr double kPreAsymptoticProduct = 0.05;

// --- Phase drift of a long run, harness/study/phase_drift.hpp --------------------------------
// No constant: the band 2*S*sin(drift/2) +- D of each step's error is derived from the law's
// eigenvalues and the closed form (an upper bound, and a lower one from the last oscillation),
// widened only by the reference's rounding (kOrderMeasurableFactor own-law tolerances plus its
// precision part). The drift is the cause when its part reaches drift_significant_ratio() = 0.155
// of D at the coarser step of the last pair (derived from kFirstOrderHigh). Measured (`dropcheck
// check scenarios/extreme/long_run.toml --engine ours-f64`): errors 1.505, 1.451, 0.4865, 0.1261 m
// at h = 1/60 .. 1/480 in the bands [1.462, 1.543], [1.425, 1.465], [0.4672, 0.4871],
// [0.1163, 0.1262] m; at the fine steps the error sits 0.6 mm and 0.1 mm under the upper bound (the
// law's phase offset adds to the drift almost in phase at the run's end), which is why the band is
// derived rather than a fixed fraction.

// --- Landing, harness/study/sweep.hpp (landing) ----------------------------------------------
// A landing may rise at most this far above the engine's rest height after first contact (m).
// Measured: <= 2e-7 m on every contact scene and engine except MuJoCo's defaults (docs/engines.md).
inline constexpr double kMaxRebound = 1e-3;
// First contact may come this many steps from the step the engine's own law predicts (the contact
// itself rounds the crossing to a step; Box2D's skin meets the floor one step early).
inline constexpr long kContactStepSlack = 1;
// How far a run may be from its engine's climb path at any step (m; harness/oracles/landing.hpp
// climb_path: DART's capped push-out). Measured on drop_on_floor and drop_on_floor_undamped at
// 1/30 to 1/240: 2.3e-14 m at worst (tests/adapters/dart_test.cpp); a cap twice DART's is 2 mm off.
inline constexpr double kClimbPath = 1e-9;
// How far a landing may be from its engine's replayed force law (harness/oracles/landing.hpp
// replayed_landing_path: Simbody's brick penalty) at any step, m: the run and the replay share
// every step but round apart, and impacts and creep amplify the rounding. Measured over the six box
// contact scenes at 1/30 to 1/240: 4.7e-9 m at worst (incline_hold, incline_slide at 1/240), the
// landings 2.9e-13 m (tests/adapters/simbody_test.cpp); a friction 2 % off is 1e-4 m off.
inline constexpr double kReplayedPath = 1e-6;

// --- Regression tier 2, harness/guard/regression.cpp --------------------------------------------
// Absolute tolerance on samples of a fresh run against its baseline, by scalar. Measured: Debug
// against CI builds max |dx| = 0 (ours has -ffp-contract=off); with FMA contraction forced on
// 1.1e-14 m (f64) and 4.8e-7 m (f32) after 3 s. Below what any change of scheme does (moving the
// damping: 2.8e-3 m after 10 steps).
inline constexpr double kRegressionF32 = 1e-4, kRegressionF64 = 1e-9;
}  // namespace dropcheck::tolerance
