// Fuzz target: the scene loader (harness/scene/scene_loader.cpp) on arbitrary bytes. Any input must
// either load or be refused with InputError; any other exception, a crash or a sanitizer report is
// a bug. A scene that loads also goes through the run pre-checks (harness/run/run_limits.cpp) for
// an f32 and an f64 engine, which read every value of it. Built by scripts/fuzz.sh (libFuzzer,
// clang) and by fuzz/CMakeLists.txt (replay driver, any compiler).
#include <cstddef>
#include <cstdint>
#include <string>

#include "harness/core/input_error.hpp"
#include "harness/run/run_limits.hpp"
#include "harness/scene/scene_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dropcheck::Scene scene;
  try {
    scene = dropcheck::parse_scene(text, "fuzz.toml");
  } catch (const dropcheck::InputError&) {
    return 0;
  }
  for (dropcheck::Scalar scalar : {dropcheck::Scalar::f32, dropcheck::Scalar::f64}) {
    dropcheck::EngineInfo info;
    info.name = "fuzz";
    info.scalar = scalar;
    for (const dropcheck::Timestep& h : scene.timesteps) {
      (void)dropcheck::run_refusal(info, scene, h.seconds, {});
      (void)dropcheck::run_refusal(info, scene, h.seconds / 4, {});  // check's h/4
    }
  }
  return 0;
}
