#include "harness/core/engine.hpp"

namespace dropcheck {

std::string Engine::cannot_run(const Scene& scene) const {
  const Capabilities caps = info().capabilities;
  if (scene.world.contacts && !caps.contacts) return "no contacts";
  if (caps.planar_only && !is_planar(scene)) return "not planar";
  return {};
}

const char* to_string(Scalar scalar) { return scalar == Scalar::f32 ? "f32" : "f64"; }

}  // namespace dropcheck
