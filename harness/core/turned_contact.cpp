#include "harness/core/turned_contact.hpp"

namespace dropcheck {

std::string describe(TurnedContact c) {
  switch (c) {
    case TurnedContact::not_declared:
      return "not declared";
    case TurnedContact::mean_corner:
      return "one impulse at the mean of the corners in the floor";
  }
  return "not declared";
}

}  // namespace dropcheck
