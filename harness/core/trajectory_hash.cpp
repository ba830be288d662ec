#include "harness/core/trajectory_hash.hpp"

#include <bit>
#include <cstdio>

namespace dropcheck {
namespace {

// FNV-1a 64: h = (h XOR byte) * 0x100000001b3, starting from 0xcbf29ce484222325.
struct Fnv1a {
  std::uint64_t h = 0xcbf29ce484222325ull;
  void add_byte(unsigned char byte) {
    h ^= byte;
    h *= 0x100000001b3ull;
  }
  void add(std::uint64_t word) {
    for (int i = 0; i < 8; ++i) add_byte(static_cast<unsigned char>(word >> (8 * i)));
  }
  void add(double d) { add(std::bit_cast<std::uint64_t>(d == 0.0 ? 0.0 : d)); }  // -0 as +0
  void add(const Vec3& v) {
    for (int i = 0; i < 3; ++i) add(v[i]);
  }
};

std::string hex16(std::uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace

std::uint64_t trajectory_hash(const Trajectory& t) {
  Fnv1a f;
  for (std::size_t s = 0; s < t.samples(); ++s) {
    f.add(static_cast<std::uint64_t>(t.recorded[s]));
    for (std::size_t b = 0; b < t.bodies(); ++b) {
      f.add(t.at(s, b).position);
      f.add(t.at(s, b).velocity);
      if (t.rotates) {
        const RotationState& r = t.rotation_at(s, b);
        for (double d :
             {r.orientation.w(), r.orientation.x(), r.orientation.y(), r.orientation.z()})
          f.add(d);
        f.add(r.angular_velocity);
      }
    }
  }
  return f.h;
}

std::string trajectory_hash_hex(const Trajectory& t) {
  return hex16(trajectory_hash(t));
}

std::uint64_t fnv1a(std::string_view bytes) {
  Fnv1a f;
  for (char c : bytes) f.add_byte(static_cast<unsigned char>(c));
  return f.h;
}

std::string fnv1a_hex(std::string_view bytes) {
  return hex16(fnv1a(bytes));
}

}  // namespace dropcheck
