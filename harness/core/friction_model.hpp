// How a contact solver bounds the friction force f of one contact with normal force N: each
// engine's member (EngineInfo::friction_model), and what the contact laws predict for it
// (harness/oracles/contact_laws.hpp, docs/contact.md).
#pragma once

namespace dropcheck {

enum class FrictionModel {
  cone,         // |f| <= mu*N: friction opposes the slip, whatever its direction
  box_pyramid,  // |f_1| <= mu*N and |f_2| <= mu*N on two fixed tangent axes, independently
  sum_pyramid,  // |f_1| + |f_2| <= mu*N: the pyramid whose edges are n +- mu*t_i
};

// "cone", "box pyramid", "sum pyramid".
const char* to_string(FrictionModel model);

}  // namespace dropcheck
