// Tests harness/plan/axes.cpp where it meets the scene loader: a cell's scene is loaded from the
// scene text with the axes' keys set.
#include "harness/plan/axes.hpp"

#include <catch2/catch.hpp>
#include <string>
#include <vector>

TEST_CASE("a scene-key axis that sets an [expect] figure quotes its shortest text", "[plan]") {
  const std::string text =
      "description = \"{a} as written\"\nduration = 1.0\n[expect]\na = 1.50\n"
      "[world]\ngravity = [0.0, -9.8, 0.0]\n[[body]]\nname = \"cube\"\nposition = [0.0, 1.0, "
      "0.0]\n";
  const std::vector<dropcheck::Axis> none;
  CHECK(dropcheck::setup_cell(text, "x.toml", "ours", none, {}).scene.description ==
        "1.50 as written");
  const std::vector<dropcheck::Axis> axes = {{dropcheck::AxisKind::scene_key, "expect.a", {"2.5"}}};
  const std::vector<std::string> values = {"2.5"};
  const dropcheck::CellSetup c = dropcheck::setup_cell(text, "x.toml", "ours", axes, values);
  CHECK(c.scene.description == "2.5 as written");  // no text in the file: the shortest
  CHECK(c.scene.expect.at("a").value == 2.5);
}
