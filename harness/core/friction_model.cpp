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

}  // namespace dropcheck
