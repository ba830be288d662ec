// Tests to_string(Capabilities) (harness/core/engine.hpp): the one text `dropcheck engines` and the
// report's engine table print for what an engine can run.
#include <catch2/catch.hpp>

#include "harness/core/engine.hpp"

using dropcheck::Capabilities;
using dropcheck::Rotation;

TEST_CASE("an engine's capabilities read as free flight plus what it adds", "[engine]") {
  CHECK(to_string(Capabilities{}) == "free flight");
  CHECK(to_string(Capabilities{.contacts = true, .rotation = Rotation::full}) ==
        "free flight, contacts, 3-D rotation");
  CHECK(to_string(Capabilities{.planar_only = true, .rotation = Rotation::spin_z}) ==
        "free flight, 2-D (x-y plane), turns about z");
}
