// How an engine holds a resting stack of boxes (EngineInfo::stack_law): what its contacts add to
// the ideal answer, every body at its geometric rest height and nothing moving
// (harness/oracles/stack.hpp, docs/contact.md "Stacks").
//
// A contact carrying the weight W of the bodies above it, between a body of mass m_a and the one
// under it (m_b; a static floor has 1/m_b = 0), sinks in the steady state by
//   compliance*h*W/points                        constraint force mixing over error reduction:
//                                                (CFM/h)*f = (ERP/h^2)*depth per contact point,
//                                                f = W/points (ODE: CFM/ERP = 1e-10/0.2)
// + soft*(tau_steps*h)^2*W*(1/m_a + 1/m_b)       a soft contact's sag (MuJoCo: the regulariser
//                                                (1 - d)/d*A_ii balances the reference
//                                                acceleration k*d*depth, k = 1/(d^2*tau^2); A_ii =
//                                                (1 + mu^2)/m over 4 pyramid edges at 4 points)
// and rests engine.rest_offset higher per contact (Box2D's skins). An iterative solver (sequential
// impulse, Gauss-Seidel) sweeps the contacts `iterations` times a step; between a body and the
// load L above it one sweep leaves L/(L + m) of the error (the iteration matrix of the pair's two
// contacts), so past (L/(L + m))^iterations > 1/2 it cannot hold the stack: a named limit.
#pragma once

#include <string>

namespace dropcheck {

struct StackLaw {
  double compliance = 0.0;  // m/(N*s): CFM/ERP of a contact point (0: rigid)
  int points = 4;           // contact points under a box face
  double soft = 0.0;        // (1 - d)*(1 + mu^2)/rows of a soft contact (0: none)
  double tau_steps = 0.0;   // its time constant in steps
  int iterations = 0;       // sweeps of an iterative solver per step (0: converges every step)
  // What an iterative solver leaves of a stack it holds, stated per engine from measurement (the
  // figures beside each adapter's values): a sink beyond the steady state above, the largest
  // horizontal drift over the run, and the largest speed and position range in the last 2 s.
  double sink_bound = 1e-3;   // m (an engine that states nothing: the landing's default band)
  double drift_bound = 1e-3;  // m
  double still_bound = 1e-3;  // m/s and m
};

// The steady-state sink (m) of one contact carrying weight W (N) between masses m_a above and m_b
// below (m_b = 0 for a static floor), at step h.
double contact_sink(const StackLaw& law, double weight, double m_above, double m_below, double h);

// The fraction of the error one step's sweeps leave between a body of mass m and load L (kg) above
// it: (L/(L + m))^iterations; 0 for a solver that converges.
double sweep_residual(const StackLaw& law, double load, double m);

// "rigid", "sinks CFM/ERP*h*W/4 per contact", "sags 7.8e-06*(2h)^2*W*(1/m_a + 1/m_b)", "10
// sweeps", the members set.
std::string describe(const StackLaw& law);

}  // namespace dropcheck
