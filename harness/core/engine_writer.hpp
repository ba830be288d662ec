// StateWriter: how an Engine::read_append override writes states from the engine's own arrays into
// the unwritten states it appended (StateBuffer) and checks them for NaN/Inf in the same pass.
//
// Per body-step this saves, against read() then all_finite(): the second pass over the states just
// written, and, for kept states, the cache: a normal store first reads the line it writes into the
// cache (read for ownership) and evicts the engine's own arrays; a streamed (non-temporal) store
// writes whole lines to memory directly. bench/loop_bench.cpp, N = 1000, load ~2, min of 6, ns per
// body-step, first and last kept / every step kept: ours 7.43 / 11.08 before, 5.89 / 6.20 with it.
// Header-only: the calls must inline into the adapter's loop.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "harness/core/engine.hpp"

namespace dropcheck {

// Writes pairs of doubles into consecutive 16-byte slots of a record of Slots pairs, in order,
// and keeps the NaN/Inf check of every number written: the shared part of StateWriter and
// RotationWriter. Streamed: with non-temporal stores, which need `out` 16-byte aligned (the
// constructor throws std::invalid_argument otherwise).
template <bool Streamed, int Slots>
class PairWriter {
 public:
  explicit PairWriter(double* out) : out_(out) {
    if (Streamed && reinterpret_cast<std::uintptr_t>(out) % 16 != 0)
      throw std::invalid_argument("streamed states must be 16-byte aligned");
  }

  // True when every number put was finite. Streamed stores are not fenced here (an sfence waits
  // for them to reach memory: 300+ ns per step, bench N = 1); this thread reads them back as
  // written, and the runner fences once per run (end_streamed_writes) before any other thread or
  // process may read them.
  bool all_finite() const {
#if defined(__SSE2__)
    __m128i all = any_[0];
    for (int k = 1; k < Slots; ++k) all = _mm_or_si128(all, any_[k]);
    return _mm_movemask_pd(_mm_castsi128_pd(all)) == 0;  // the sign bits (see pair)
#else
    std::uint64_t all = 0;
    for (const std::uint64_t a : any_) all |= a;
    return (all >> 63) == 0;
#endif
  }

 protected:
  // Writes slot `slot` of the current record.
#if defined(__SSE2__)
  void pair(int slot, double lo, double hi) {
    const __m128d v = _mm_set_pd(hi, lo);
    if constexpr (Streamed)
      _mm_stream_pd(out_ + 2 * slot, v);
    else
      _mm_storeu_pd(out_ + 2 * slot, v);
    const __m128i field = _mm_and_si128(_mm_castpd_si128(v), _mm_set1_epi64x(kExponent));
    any_[slot] = _mm_or_si128(any_[slot], _mm_add_epi64(field, _mm_set1_epi64x(kUnit)));
  }
#else
  void pair(int slot, double lo, double hi) {
    out_[2 * slot] = lo;
    out_[2 * slot + 1] = hi;
    any_[slot] |= ((std::bit_cast<std::uint64_t>(lo) & kExponent) + kUnit) |
                  ((std::bit_cast<std::uint64_t>(hi) & kExponent) + kUnit);
  }
#endif
  // Moves on to the next record.
  void next() {
    out_ += 2 * Slots;
  }

 private:
  // A double is NaN or Inf exactly when its 11 exponent bits are all ones; adding one exponent
  // unit to (bits & exponent mask) then carries into the sign bit, so the OR of those sums over
  // all numbers has its sign bit set iff some number is not finite (as all_finite, engine.cpp).
  // One accumulator per slot: independent OR chains.
  static constexpr std::uint64_t kExponent = 0x7ff0000000000000u, kUnit = 0x0010000000000000u;
#if defined(__SSE2__)
  __m128i any_[Slots] = {};
#else
  std::uint64_t any_[Slots] = {};
#endif
  double* out_;  // the current record's first number
};

// Writes states in order into out[0], out[1], ...; Streamed: with non-temporal stores (for
// StateUse::kept), which need `out` 16-byte aligned: true of any state of a StateBuffer (64-byte
// aligned blocks, 48-byte states).
template <bool Streamed>
class StateWriter : public PairWriter<Streamed, 3> {
  using Base = PairWriter<Streamed, 3>;

 public:
  explicit StateWriter(BodyState* out) : Base(reinterpret_cast<double*>(out)) {
    static_assert(sizeof(BodyState) == 6 * sizeof(double));
  }

  // Writes the next state: position p, velocity v.
  void put(double px, double py, double pz, double vx, double vy, double vz) {
    this->pair(0, px, py);
    this->pair(1, pz, vx);
    this->pair(2, vy, vz);
    this->next();
  }

  // True when every number put was finite.
  bool finish() const { return this->all_finite(); }
};

// Writes rotational states in order into out[0], out[1], ... (a RotationBuffer: 64-byte aligned,
// one 64-byte state per cache line, so streamed stores write whole lines), checking in the same
// pass that every number is finite and every orientation a unit quaternion (rotation_sound).
// The eighth double of each state is padding (Eigen aligns the quaternion to 16 bytes): written as
// +0.0 so that a streamed line is written whole.
template <bool Streamed>
class RotationWriter : public PairWriter<Streamed, 4> {
  using Base = PairWriter<Streamed, 4>;

 public:
  explicit RotationWriter(RotationState* out) : Base(reinterpret_cast<double*>(out)) {
    static_assert(sizeof(RotationState) == 8 * sizeof(double));
    static_assert(offsetof(RotationState, angular_velocity) == 4 * sizeof(double));
  }

  // Writes the next state: orientation q = (w, x, y, z), world angular velocity a. Quat stores
  // its coefficients as (x, y, z, w).
  void put(double qw, double qx, double qy, double qz, double ax, double ay, double az) {
    this->pair(0, qx, qy);
    this->pair(1, qz, qw);
    this->pair(2, ax, ay);
    this->pair(3, az, 0.0);
    this->next();
    const double n2 = qw * qw + qx * qx + qy * qy + qz * qz;
    off_unit_ |= !(n2 >= kUnitNorm2Min) | !(n2 <= kUnitNorm2Max);  // NaN compares false: off
  }

  // True when every number put was finite and every orientation a unit quaternion.
  bool finish() const { return this->all_finite() && !off_unit_; }

 private:
  bool off_unit_ = false;
};

// Appends `count` unwritten states to `out` and has `write` put them, through a StateWriter that
// streams when `use` is kept: the body of an Engine::read_append override. `write` takes the
// writer (StateWriter<true> or <false>) and returns its finish().
template <typename Write>
bool append_states(StateBuffer& out, std::size_t count, StateUse use, Write&& write) {
  const std::size_t at = out.size();
  out.resize(at + count);  // unwritten
  BodyState* added = out.data() + at;
  return use == StateUse::kept ? write(StateWriter<true>(added)) : write(StateWriter<false>(added));
}

// The same for rotational states (Engine::read_rotation_append, RotationWriter).
template <typename Write>
bool append_rotations(RotationBuffer& out, std::size_t count, StateUse use, Write&& write) {
  const std::size_t at = out.size();
  out.resize(at + count);  // unwritten
  RotationState* added = out.data() + at;
  return use == StateUse::kept ? write(RotationWriter<true>(added))
                               : write(RotationWriter<false>(added));
}

// Orders every streamed store made so far by this thread before its later stores (sfence): call
// once after the last StateWriter<true> of a run, before the states are handed to anyone else.
inline void end_streamed_writes() {
#if defined(__SSE2__)
  _mm_sfence();
#endif
}

}  // namespace dropcheck
