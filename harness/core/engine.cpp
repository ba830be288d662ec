#include "harness/core/engine.hpp"

#include <bit>
#include <cmath>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace dropcheck {

namespace {

// Engine::cannot_run's refusals that a capability lifts, each beside the protocol's word for it
// (docs/protocol.md, `capabilities`).
constexpr const char* kNoContacts = "no contacts";
constexpr const char* kNoSpheres = "spheres: this engine's adapter builds boxes only";
constexpr const char* kNoFriction = "friction: this engine's adapter does not map it";
constexpr const char* kNoRestitution = "restitution: this engine's adapter does not map it";
constexpr const char* kNoRotation = "rotation: this engine's adapter does not rotate bodies";
constexpr const char* kOnlyZ = "rotation: a 2-D engine turns bodies about z only";

}  // namespace

std::string capability_lifting(const std::string& refusal) {
  if (refusal == kNoContacts) return "contacts";
  if (refusal == kNoSpheres) return "spheres";
  if (refusal == kNoFriction) return "friction";
  if (refusal == kNoRestitution) return "restitution";
  if (refusal == kNoRotation || refusal == kOnlyZ) return "rotation";
  return {};
}

std::string Engine::cannot_run(const Scene& scene) const {
  const EngineInfo self = info();
  const Capabilities& caps = self.capabilities;
  if (scene.world.contacts && !caps.contacts) return kNoContacts;
  if (caps.planar_only && !is_planar(scene)) return "not planar";
  if (has_spheres(scene) && !caps.spheres) return kNoSpheres;
  const Material m = scene_material(scene);
  if (m.friction && !caps.friction) return kNoFriction;
  if (m.restitution && !caps.restitution) return kNoRestitution;
  if (self.law.scheme == Scheme::ErrorControlled)
    for (const Force& f : scene.forces)
      if (std::holds_alternative<Spring>(f.law))
        return "springs: the harness sets a spring's force once per step, and an "
               "error-controlled integrator would integrate that held force, not the spring";
  if (!needs_rotation(scene)) return {};
  if (caps.rotation == Rotation::none) return kNoRotation;
  if (caps.rotation == Rotation::spin_z && !spins_about_z(scene)) return kOnlyZ;
  return {};
}

RotationState turn_about_z(double angle, double w_z) {
  return {Quat(std::cos(angle / 2), 0.0, 0.0, std::sin(angle / 2)), Vec3(0.0, 0.0, w_z)};
}

std::string to_string(const Capabilities& c) {
  std::string out = c.contacts ? "free flight, contacts" : "free flight";
  if (c.planar_only) out += ", 2-D (x-y plane)";
  if (c.rotation == Rotation::full) out += ", 3-D rotation";
  if (c.rotation == Rotation::spin_z) out += ", turns about z";
  if (c.friction) out += ", friction";
  if (c.restitution) out += ", restitution";
  if (c.spheres) out += ", spheres";
  return out;
}

void Engine::set_torques(std::span<const Vec3>) {
  throw EngineError("this engine takes no torques");
}

void Engine::read_rotation(std::span<RotationState>) const {
  throw EngineError("this engine does not report rotation");
}

namespace {

constexpr std::align_val_t kStateAlignment{64};           // one cache line
constexpr std::size_t kHugePage = std::size_t{2} << 20;   // x86-64 transparent huge page
constexpr std::size_t kHugeBlock = std::size_t{4} << 20;  // from this size on: huge pages

}  // namespace

// Huge pages: a trajectory kept every step is written once, front to back, into fresh memory; with
// 4 KiB pages each page costs a fault (and the kernel's zeroing) per 85 states. The advice covers
// the whole 2 MiB pages inside the block (a block keeps malloc's own placement, which reuses freed
// memory: 2 MiB-aligned blocks came from a fresh mapping each time, every run faulting again). It
// is best effort: where THP is off it changes nothing, and a failure is ignored. Measured on
// `dropcheck run scenarios/extreme/long_run.toml --engine ours` (20 MB kept, load ~2): 2293 page
// faults instead of 11483, stepping loop 15.7 ms instead of 18.5 ms (min of 6).
void* allocate_states(std::size_t bytes) {
  void* p = ::operator new(bytes, kStateAlignment);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (bytes >= kHugeBlock) {
    const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t first = (begin + kHugePage - 1) / kHugePage * kHugePage;
    const std::uintptr_t last = (begin + bytes) / kHugePage * kHugePage;
    if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  }
#endif
  return p;
}

void free_states(void* p, std::size_t) noexcept {
  ::operator delete(p, kStateAlignment);
}

// A double is NaN or Inf exactly when its 11 exponent bits are all ones; adding one to the exponent
// field then carries into the sign bit, so the OR of (bits & exponent mask) + (one exponent unit)
// over all numbers has the sign bit set iff some number is not finite. Integer AND, ADD and OR
// vectorise. Eight independent accumulators (one body and a third per round): with a single one
// every OR waits for the previous one, and the pass cost half of ours's own step (perf, N = 1000).
bool all_finite(std::span<const BodyState> states) {
  static_assert(sizeof(BodyState) == 6 * sizeof(double));
  constexpr std::uint64_t kExponent = 0x7ff0000000000000u, kUnit = 0x0010000000000000u;
  constexpr std::size_t kLanes = 8;
  const auto* d = reinterpret_cast<const double*>(states.data());
  const std::size_t n = 6 * states.size();
  std::uint64_t any[kLanes] = {};
  std::size_t k = 0;
  for (; k + kLanes <= n; k += kLanes)
    for (std::size_t j = 0; j < kLanes; ++j)
      any[j] |= (std::bit_cast<std::uint64_t>(d[k + j]) & kExponent) + kUnit;
  for (; k < n; ++k) any[0] |= (std::bit_cast<std::uint64_t>(d[k]) & kExponent) + kUnit;
  std::uint64_t all = 0;
  for (const std::uint64_t a : any) all |= a;
  return (all >> 63) == 0;
}

// The same exponent test as for BodyState, over the 7 numbers of each rotational state (a
// RotationState is padded to 64 bytes, so its numbers are read by name, not as one array).
bool all_finite(std::span<const RotationState> rotations) {
  constexpr std::uint64_t kExponent = 0x7ff0000000000000u, kUnit = 0x0010000000000000u;
  std::uint64_t any = 0;
  for (const RotationState& r : rotations) {
    const double d[7] = {r.orientation.w(),     r.orientation.x(),      r.orientation.y(),
                         r.orientation.z(),     r.angular_velocity.x(), r.angular_velocity.y(),
                         r.angular_velocity.z()};
    for (const double x : d) any |= (std::bit_cast<std::uint64_t>(x) & kExponent) + kUnit;
  }
  return (any >> 63) == 0;
}

bool rotations_sound(std::span<const RotationState> rotations) {
  bool off_unit = false;
  for (const RotationState& r : rotations) {
    const double n2 = r.orientation.squaredNorm();
    off_unit |= !(n2 >= kUnitNorm2Min) | !(n2 <= kUnitNorm2Max);  // NaN compares false: off
  }
  return all_finite(rotations) && !off_unit;
}

bool Engine::read_rotation_append(std::size_t bodies, RotationBuffer& out, StateUse) const {
  const std::size_t at = out.size();
  out.resize(at + bodies);  // unwritten: read_rotation() writes every one
  const std::span<RotationState> added = std::span(out).subspan(at, bodies);
  read_rotation(added);
  return rotations_sound(added);
}

bool Engine::read_append(std::size_t bodies, StateBuffer& out, StateUse) const {
  const std::size_t at = out.size();
  out.resize(at + bodies);  // unwritten: read() writes every one
  const std::span<BodyState> added = std::span(out).subspan(at, bodies);
  read(added);
  return all_finite(added);
}

const char* to_string(Scalar scalar) {
  return scalar == Scalar::f32 ? "f32" : "f64";
}

const char* to_string(Rotation rotation) {
  switch (rotation) {
    case Rotation::spin_z:
      return "about z";
    case Rotation::full:
      return "3-D";
    case Rotation::none:
      break;
  }
  return "none";
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
