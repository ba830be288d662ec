// Tests harness/core/engine_writer.hpp (StateWriter) and the state storage of engine.hpp
// (StateBuffer, all_finite) and RotationWriter with rotations_sound: what Engine::read_append and
// Engine::read_rotation_append overrides write through.
#include "harness/core/engine_writer.hpp"

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>

namespace {

using dropcheck::BodyState;
using dropcheck::StateBuffer;
using dropcheck::StateWriter;
using dropcheck::Vec3;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Puts `states` through a StateWriter<Streamed> into fresh slots of `out`; returns finish().
template <bool Streamed>
bool write_states(StateBuffer& out, const std::vector<std::array<double, 6>>& states) {
  const std::size_t at = out.size();
  out.resize(at + states.size());
  StateWriter<Streamed> w(out.data() + at);
  for (const std::array<double, 6>& s : states) w.put(s[0], s[1], s[2], s[3], s[4], s[5]);
  return w.finish();
}

// Every finite extreme a state may hold: the largest and smallest normal, a subnormal, -0.
const std::vector<std::array<double, 6>> kFinite = {
    {1.0, -2.5, 3.25, -0.0, 0.0, 1e-300},
    {std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(),
     std::numeric_limits<double>::min(), std::numeric_limits<double>::denorm_min(), 7.0, -8.0},
    {0.1, 0.2, 0.3, 0.4, 0.5, 0.6},
};

template <bool Streamed>
void check_writes_exactly() {
  StateBuffer out;
  out.push_back({Vec3(9, 9, 9), Vec3(9, 9, 9)});  // written before: left as it was
  CHECK(write_states<Streamed>(out, kFinite));
  REQUIRE(out.size() == 4);
  CHECK(out[0].position == Vec3(9, 9, 9));
  for (std::size_t i = 0; i < kFinite.size(); ++i) {
    const BodyState& s = out[i + 1];
    for (int k = 0; k < 3; ++k) {
      CHECK(std::bit_cast<std::uint64_t>(s.position[k]) ==
            std::bit_cast<std::uint64_t>(kFinite[i][k]));
      CHECK(std::bit_cast<std::uint64_t>(s.velocity[k]) ==
            std::bit_cast<std::uint64_t>(kFinite[i][k + 3]));
    }
  }
}

template <bool Streamed>
void check_finds_every_non_finite() {
  for (const double bad : {kNaN, -kNaN, kInf, -kInf}) {
    for (std::size_t body = 0; body < kFinite.size(); ++body) {
      for (int k = 0; k < 6; ++k) {
        std::vector<std::array<double, 6>> states = kFinite;
        states[body][k] = bad;
        StateBuffer out;
        INFO("body " << body << ", number " << k << ", value " << bad);
        CHECK_FALSE(write_states<Streamed>(out, states));
        CHECK(std::bit_cast<std::uint64_t>(
                  reinterpret_cast<const double*>(out.data())[6 * body + k]) ==
              std::bit_cast<std::uint64_t>(bad));  // written all the same
      }
    }
  }
}

}  // namespace

TEST_CASE("a state writer writes every number bit for bit, streamed or not", "[engine]") {
  check_writes_exactly<false>();
  check_writes_exactly<true>();
}

TEST_CASE("a state writer reports a NaN or an Inf in any number of any state", "[engine]") {
  check_finds_every_non_finite<false>();
  check_finds_every_non_finite<true>();
}

TEST_CASE("a state writer with nothing put reports all finite", "[engine]") {
  StateBuffer out;
  CHECK(write_states<true>(out, {}));
  CHECK(write_states<false>(out, {}));
  CHECK(out.empty());
}

TEST_CASE("a streamed state writer refuses storage that is not 16-byte aligned", "[engine]") {
  alignas(16) std::array<double, 14> raw{};
  auto* odd = reinterpret_cast<BodyState*>(raw.data() + 1);  // 8 bytes past a 16-byte boundary
  CHECK_THROWS_AS(StateWriter<true>(odd), std::invalid_argument);
  StateWriter<false> normal(odd);  // normal stores take any double-aligned storage
  normal.put(1, 2, 3, 4, 5, 6);
  CHECK(normal.finish());
  CHECK(raw[1] == 1.0);
  CHECK(raw[6] == 6.0);
}

TEST_CASE("a state buffer is cache-line aligned and keeps its states when it grows", "[engine]") {
  StateBuffer b;
  for (int i = 0; i < 1000; ++i) {
    b.push_back({Vec3(i, 0, 0), Vec3(0, 0, -i)});
    CHECK(reinterpret_cast<std::uintptr_t>(b.data()) % 64 == 0);
  }
  b.resize(1500);  // unwritten: written below before anything reads them
  for (std::size_t i = 1000; i < b.size(); ++i) b[i] = {Vec3(i, 0, 0), Vec3(0, 0, -1.0 * i)};
  const StateBuffer copy = b;
  REQUIRE(copy.size() == 1500);
  for (std::size_t i = 0; i < copy.size(); ++i) {
    CHECK(copy[i].position.x() == static_cast<double>(i));
    CHECK(copy[i].velocity.z() == -static_cast<double>(i));
  }
  const StateBuffer three(3);  // values unwritten: only the size and the placement are checked
  CHECK(three.size() == 3);
  CHECK(reinterpret_cast<std::uintptr_t>(three.data()) % 64 == 0);
}

TEST_CASE("all_finite finds a NaN or an Inf anywhere, beyond the eight-number rounds too",
          "[engine]") {
  for (std::size_t n : {1u, 2u, 3u, 5u}) {
    StateBuffer b(n, BodyState{Vec3(1, 2, 3), Vec3(4, 5, 6)});
    CHECK(dropcheck::all_finite(b));
    for (std::size_t i = 0; i < 6 * n; ++i) {
      StateBuffer bad = b;
      reinterpret_cast<double*>(bad.data())[i] = (i % 2 != 0U) ? kNaN : -kInf;
      INFO("n " << n << ", number " << i);
      CHECK_FALSE(dropcheck::all_finite(bad));
    }
  }
  CHECK(dropcheck::all_finite(std::span<const dropcheck::BodyState>{}));
}

namespace {

using dropcheck::Quat;
using dropcheck::RotationBuffer;
using dropcheck::RotationState;
using dropcheck::RotationWriter;

// (qw, qx, qy, qz, wx, wy, wz) per state.
using Turn = std::array<double, 7>;

// Puts `turns` through a RotationWriter<Streamed> into fresh slots of `out`; returns finish().
template <bool Streamed>
bool write_turns(RotationBuffer& out, const std::vector<Turn>& turns) {
  const std::size_t at = out.size();
  out.resize(at + turns.size());
  RotationWriter<Streamed> w(out.data() + at);
  for (const Turn& r : turns) w.put(r[0], r[1], r[2], r[3], r[4], r[5], r[6]);
  return w.finish();
}

// Unit quaternions at the edges of what a run accepts, and finite extremes of angular velocity.
const std::vector<Turn> kSound = {
    {1.0, 0.0, 0.0, 0.0, 0.0, -0.0, 1e-300},
    {0.5, -0.5, 0.5, -0.5, std::numeric_limits<double>::max(), -3.0, 4.0},
    {0.0, 0.6, 0.0, 0.8 * (1 + 0.9e-4), 0.1, 0.2, 0.3},  // |q| - 1 = 0.64 * 0.9e-4: inside
};

template <bool Streamed>
void check_turns_written_exactly() {
  RotationBuffer out;
  out.push_back({Quat(0, 1, 0, 0), Vec3(9, 9, 9)});  // written before: left as it was
  CHECK(write_turns<Streamed>(out, kSound));
  REQUIRE(out.size() == 4);
  CHECK(out[0].orientation.x() == 1.0);
  CHECK(out[0].angular_velocity == Vec3(9, 9, 9));
  for (std::size_t i = 0; i < kSound.size(); ++i) {
    const RotationState& r = out[i + 1];
    const double got[7] = {r.orientation.w(),     r.orientation.x(),      r.orientation.y(),
                           r.orientation.z(),     r.angular_velocity.x(), r.angular_velocity.y(),
                           r.angular_velocity.z()};
    for (int k = 0; k < 7; ++k)
      CHECK(std::bit_cast<std::uint64_t>(got[k]) == std::bit_cast<std::uint64_t>(kSound[i][k]));
  }
  CHECK(dropcheck::rotations_sound(std::span(out).subspan(1)));
}

template <bool Streamed>
void check_turns_unsound_found() {
  for (const double bad : {kNaN, -kNaN, kInf, -kInf}) {
    for (std::size_t body = 0; body < kSound.size(); ++body) {
      for (int k = 0; k < 7; ++k) {
        std::vector<Turn> turns = kSound;
        turns[body][k] = bad;
        RotationBuffer out;
        INFO("body " << body << ", number " << k << ", value " << bad);
        CHECK_FALSE(write_turns<Streamed>(out, turns));
        CHECK_FALSE(dropcheck::rotations_sound(out));
      }
    }
  }
  // Off the unit sphere: zero, doubled, and just beyond the slack on either side.
  for (const double scale : {0.0, 2.0, 1 + 1.1e-4, 1 - 1.1e-4}) {
    std::vector<Turn> turns = kSound;
    for (int k = 0; k < 4; ++k) turns[1][k] *= scale;
    RotationBuffer out;
    INFO("orientation scaled by " << scale);
    CHECK_FALSE(write_turns<Streamed>(out, turns));
    CHECK_FALSE(dropcheck::rotations_sound(out));
  }
}

}  // namespace

TEST_CASE("a rotation writer writes every number bit for bit, streamed or not", "[engine]") {
  check_turns_written_exactly<false>();
  check_turns_written_exactly<true>();
}

TEST_CASE("a rotation writer reports a NaN, an Inf or an orientation off the unit sphere",
          "[engine]") {
  check_turns_unsound_found<false>();
  check_turns_unsound_found<true>();
}

TEST_CASE("an engine's default rotation read appends, reads through read_rotation and checks",
          "[engine]") {
  struct Turning final : dropcheck::Engine {
    Quat q = Quat::Identity();
    dropcheck::EngineInfo info() const override { return {}; }
    void load(const dropcheck::Scene&, double) override {}
    void set_forces(std::span<const Vec3>) override {}
    void step() override {}
    void read(std::span<BodyState>) const override {}
    void read_rotation(std::span<RotationState> out) const override {
      for (RotationState& r : out) r = {q, Vec3(1, 2, 3)};
    }
  } engine;
  RotationBuffer out;
  CHECK(engine.read_rotation_append(2, out, dropcheck::StateUse::kept));
  REQUIRE(out.size() == 2);
  CHECK(out[1].angular_velocity == Vec3(1, 2, 3));
  engine.q.coeffs() *= 1.5;
  CHECK_FALSE(engine.read_rotation_append(1, out, dropcheck::StateUse::next_step));
  CHECK(out.size() == 3);
}
