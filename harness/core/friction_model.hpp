// How a contact solver bounds the friction force f of one contact with normal force N: each
// engine's member (EngineInfo::friction_model), and what the contact laws predict for it
// (harness/oracles/contact_laws.hpp, docs/contact.md).
#pragma once

#include <string>

namespace dropcheck {

enum class FrictionModel {
  cone,         // |f| <= mu*N: friction opposes the slip, whatever its direction
  box_pyramid,  // |f_1| <= mu*N and |f_2| <= mu*N on two fixed tangent axes, independently
  sum_pyramid,  // |f_1| + |f_2| <= mu*N: the pyramid whose edges are n +- mu*t_i
};

// Every model, in the order above.
inline constexpr FrictionModel kFrictionModels[] = {FrictionModel::cone, FrictionModel::box_pyramid,
                                                    FrictionModel::sum_pyramid};

// "cone", "box pyramid", "sum pyramid".
const char* to_string(FrictionModel model);

// The protocol's keys (docs/protocol.md): "cone", "box-pyramid", "sum-pyramid"; false for another.
const char* friction_model_key(FrictionModel model);
bool parse_friction_model_key(const std::string& key, FrictionModel& out);

}  // namespace dropcheck
