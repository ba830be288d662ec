#include "harness/core/contact_solver.hpp"

namespace dropcheck {

std::string describe(const ContactSolver& solver) {
  switch (solver.kind) {
    case ContactSolverKind::exact:
      return "solved exactly every step";
    case ContactSolverKind::box2d_2_4:
      return "Box2D 2.4 sequential impulses (" + std::to_string(solver.velocity_iterations) +
             " velocity, " + std::to_string(solver.position_iterations) +
             " position iterations, warm started), replayed";
    case ContactSolverKind::chipmunk_7:
      return "Chipmunk 7 sequential impulses (" + std::to_string(solver.velocity_iterations) +
             " iterations, cached impulses), replayed";
    case ContactSolverKind::mujoco_2_2:
      return "MuJoCo 2.2 soft contact (pyramidal cone, its convex step problem re-solved)";
    case ContactSolverKind::bullet_3:
      return "Bullet 3 sequential impulses (" + std::to_string(solver.velocity_iterations) +
             " iterations), bounded by Coulomb's law";
    case ContactSolverKind::sequential_impulses:
      return "sequential impulses (" + std::to_string(solver.velocity_iterations) +
             " iterations, declared), bounded by Coulomb's law";
    case ContactSolverKind::soft:
      return "a soft contact (declared), bounded by Coulomb's law";
    case ContactSolverKind::hunt_crossley:
      return "Simbody Hunt-Crossley force (its force law stepped as its integrator steps)";
  }
  return "unknown";
}

bool held_by_momentum(const ContactSolver& solver) {
  return solver.kind == ContactSolverKind::bullet_3 ||
         solver.kind == ContactSolverKind::sequential_impulses ||
         solver.kind == ContactSolverKind::soft;
}

}  // namespace dropcheck
