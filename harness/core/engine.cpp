#include "harness/core/engine.hpp"

namespace dropcheck {

std::string Engine::cannot_run(const Scene& scene) const {
  const Capabilities caps = info().capabilities;
  if (scene.world.contacts && !caps.contacts) return "no contacts";
  if (caps.planar_only && !is_planar(scene)) return "not planar";
  return {};
}

void Engine::read_append(std::size_t bodies, std::vector<BodyState>& out) const {
  const std::size_t at = out.size();
  out.resize(at + bodies);
  read(std::span(out).subspan(at, bodies));
}

const char* to_string(Scalar scalar) {
  return scalar == Scalar::f32 ? "f32" : "f64";
}

const char* to_string(DampingForm form) {
  switch (form) {
    case DampingForm::phi_multiply:
      return "phi multiply";
    case DampingForm::pade:
      return "Pade 1/(1 + h*c)";
    case DampingForm::per_second_power:
      return "(1 - d)^h per second";
    case DampingForm::other:
      break;
  }
  return "not copied";
}

}  // namespace dropcheck
