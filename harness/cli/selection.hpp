// Which engines a command runs on a scene: the --engine names given, or every engine compiled in.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "harness/core/engine.hpp"

namespace dropcheck {

struct SelectedEngine {
  std::string name;  // as requested (an engine file's path), or its own name when it is skipped
  std::unique_ptr<Engine> engine;  // nullptr when it cannot run the scene
  std::string skipped_because;     // why not ("not planar", "not compiled in ...")
};

// Validates `requested` (InputError for an unknown name, key "--engine"). With none requested,
// every engine compiled in; engines that cannot run `scene` come back with their reason.
std::vector<SelectedEngine> select_engines(const std::vector<std::string>& requested,
                                           const Scene& scene);

// Two engines that announce one name would share rows, columns and baseline files: refused with an
// InputError naming both. `engines`: each one's --engine value and the name it announced.
void refuse_name_clashes(const std::vector<std::pair<std::string, std::string>>& engines);

// --dt as seconds or "1/N", checked against the scene's duration; the scene's step when empty.
Timestep step_from_flag(const std::string& flag_value, const Scene& scene);

}  // namespace dropcheck
