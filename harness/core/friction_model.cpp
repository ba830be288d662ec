#include "harness/core/friction_model.hpp"

namespace dropcheck {

const char* to_string(FrictionModel model) {
  switch (model) {
    case FrictionModel::cone:
      return "cone";
    case FrictionModel::box_pyramid:
      return "box pyramid";
    case FrictionModel::sum_pyramid:
      return "sum pyramid";
  }
  return "?";
}

const char* friction_model_key(FrictionModel model) {
  switch (model) {
    case FrictionModel::cone:
      return "cone";
    case FrictionModel::box_pyramid:
      return "box-pyramid";
    case FrictionModel::sum_pyramid:
      return "sum-pyramid";
  }
  return "?";
}

bool parse_friction_model_key(const std::string& key, FrictionModel& out) {
  for (FrictionModel m : kFrictionModels)
    if (key == friction_model_key(m)) {
      out = m;
      return true;
    }
  return false;
}

}  // namespace dropcheck
