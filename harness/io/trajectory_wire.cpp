#include "harness/io/trajectory_wire.hpp"

#include <string>
#include <vector>

namespace dropcheck {
namespace {

constexpr std::uint32_t kMagic = 0x31544344;  // "DCT1"
constexpr std::uint64_t kMaxString = std::uint64_t{16}
                                     << 20;  // longer than any name a loader accepts
constexpr std::size_t kChunk = 8192;         // doubles converted per write/read of the states

template <typename T>
bool put(const WireWrite& write, const T& v) {
  return write(&v, sizeof v);
}

bool put_string(const WireWrite& write, const std::string& s) {
  return put(write, std::uint64_t{s.size()}) && write(s.data(), s.size());
}

template <typename T>
bool get(const WireRead& read, T& v) {
  return read(&v, sizeof v);
}

bool get_string(const WireRead& read, std::string& s) {
  std::uint64_t n = 0;
  if (!get(read, n) || n > kMaxString) return false;
  s.resize(n);
  return read(s.data(), n);
}

// States as 6 doubles each (x, y, z, vx, vy, vz), a chunk at a time.
bool put_states(const WireWrite& write, const Trajectory& t) {
  const std::size_t rows = t.samples() * t.bodies();
  std::vector<double> buf;
  buf.reserve(kChunk);
  for (std::size_t r = 0; r < rows; ++r) {
    const BodyState& s = t.states[r];
    for (int i = 0; i < 3; ++i) buf.push_back(s.position[i]);
    for (int i = 0; i < 3; ++i) buf.push_back(s.velocity[i]);
    if (buf.size() + 6 > kChunk || r + 1 == rows) {
      if (!write(buf.data(), buf.size() * sizeof(double))) return false;
      buf.clear();
    }
  }
  return true;
}

bool get_states(const WireRead& read, Trajectory& t, std::size_t rows) {
  t.states.clear();
  t.states.reserve(rows);
  std::vector<double> buf(kChunk - kChunk % 6);
  for (std::size_t r = 0; r < rows;) {
    const std::size_t n = std::min(rows - r, buf.size() / 6);
    if (!read(buf.data(), n * 6 * sizeof(double))) return false;
    for (std::size_t k = 0; k < n; ++k, ++r)
      t.states.push_back({Vec3(buf[6 * k], buf[6 * k + 1], buf[6 * k + 2]),
                          Vec3(buf[6 * k + 3], buf[6 * k + 4], buf[6 * k + 5])});
  }
  return true;
}

// Rotations as 7 doubles each (qw, qx, qy, qz, wx, wy, wz); they are few (rotating scenes only),
// so sent in one piece.
bool put_rotations(const WireWrite& write, const Trajectory& t) {
  std::vector<double> buf;
  buf.reserve(7 * t.rotations.size());
  for (const RotationState& r : t.rotations) {
    const Quat& q = r.orientation;
    for (double d : {q.w(), q.x(), q.y(), q.z()}) buf.push_back(d);
    for (int i = 0; i < 3; ++i) buf.push_back(r.angular_velocity[i]);
  }
  return write(buf.data(), buf.size() * sizeof(double));
}

bool get_rotations(const WireRead& read, Trajectory& t, std::size_t rows) {
  std::vector<double> buf(7 * rows);
  if (!read(buf.data(), buf.size() * sizeof(double))) return false;
  t.rotations.resize(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    const double* d = &buf[7 * r];
    t.rotations[r] = {Quat(d[0], d[1], d[2], d[3]), Vec3(d[4], d[5], d[6])};
  }
  return true;
}

}  // namespace

bool write_trajectory(const Trajectory& t, const WireWrite& write) {
  bool ok = put(write, kMagic) && put_string(write, t.engine) && put_string(write, t.scene) &&
            put(write, t.h) && put(write, t.steps) &&
            put(write, static_cast<std::int32_t>(t.status)) && put_string(write, t.failure) &&
            put(write, t.failed_step) && put(write, t.clamped_steps) &&
            put(write, t.first_clamped_step) && put(write, t.engine_steps) &&
            put(write, t.wall_seconds) && put(write, std::uint64_t{t.bodies()});
  for (std::size_t b = 0; ok && b < t.bodies(); ++b) ok = put_string(write, t.body_names[b]);
  ok = ok && put(write, std::uint64_t{t.samples()}) &&
       write(t.recorded.data(), t.samples() * sizeof(std::int64_t)) && put_states(write, t) &&
       put(write, static_cast<std::uint8_t>(t.rotates)) && (!t.rotates || put_rotations(write, t));
  return ok && put(write, kMagic);
}

bool read_trajectory(Trajectory& t, std::size_t bodies, std::int64_t max_samples,
                     const WireRead& read) {
  std::uint32_t magic = 0;
  std::int32_t status = 0;
  std::uint64_t n = 0;
  if (!get(read, magic) || magic != kMagic || !get_string(read, t.engine) ||
      !get_string(read, t.scene) || !get(read, t.h) || !get(read, t.steps) || !get(read, status) ||
      !get_string(read, t.failure) || !get(read, t.failed_step) || !get(read, t.clamped_steps) ||
      !get(read, t.first_clamped_step) || !get(read, t.engine_steps) ||
      !get(read, t.wall_seconds) || !get(read, n) || n != bodies)
    return false;
  if (status < 0 || status > static_cast<std::int32_t>(RunStatus::refused)) return false;
  t.status = static_cast<RunStatus>(status);
  t.body_names.resize(bodies);
  for (std::string& name : t.body_names)
    if (!get_string(read, name)) return false;
  if (!get(read, n) || n > static_cast<std::uint64_t>(max_samples)) return false;
  t.recorded.resize(n);
  if (!read(t.recorded.data(), n * sizeof(std::int64_t)) || !get_states(read, t, n * bodies))
    return false;
  std::uint8_t rotates = 0;
  if (!get(read, rotates) || rotates > 1) return false;
  t.rotates = rotates == 1;
  if (t.rotates && !get_rotations(read, t, n * bodies)) return false;
  return get(read, magic) && magic == kMagic;
}

}  // namespace dropcheck
