// Deterministic random numbers: every stream is derived from a tuple of keys
// (seed, view, pixel, sample, bounce, ...) so any pixel can be re-run alone.
#pragma once

#include <cstdint>
#include <initializer_list>

#include "math/vec.h"

namespace glint {

// 64-bit mix (SplitMix64 finaliser, Steele et al. 2014) used to hash keys into a seed.
constexpr uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Hashes an ordered list of keys into one 64-bit value.
constexpr uint64_t hashKeys(std::initializer_list<uint64_t> keys) {
  uint64_t h = 0x9e3779b97f4a7c15ull;
  for (uint64_t k : keys) h = mix64(h ^ mix64(k + 0x632be59bd9b4e019ull));
  return h;
}

// Maps 32 random bits to [0, 1), never 1: the top 24 bits scaled exactly.
constexpr float unitFloatFromBits(uint32_t bits) { return static_cast<float>(bits >> 8) * 0x1p-24f; }

// PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
// Algorithms for Random Number Generation"): small state, good statistics, fast.
class Rng {
 public:
  Rng() : Rng(0) {}
  explicit Rng(uint64_t seed, uint64_t stream = 0) { seedWith(seed, stream); }
  // A generator for the stream named by keys, e.g. Rng::forKeys({seed, view, pixel, sample}).
  static Rng forKeys(std::initializer_list<uint64_t> keys) { return Rng(hashKeys(keys)); }

  void seedWith(uint64_t seed, uint64_t stream = 0) {
    state_ = 0;
    increment_ = (stream << 1u) | 1u;
    nextUint();
    state_ += seed;
    nextUint();
  }

  uint32_t nextUint() {
    uint64_t old = state_;
    state_ = old * 6364136223846793005ull + increment_;
    uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
  }

  // Skips `delta` outputs in O(log delta) steps, as `delta` calls of nextUint would: the
  // LCG step applied delta times is again an affine map, built by repeated squaring
  // (F. Brown, "Random number generation with arbitrary strides", 1994).
  void advance(uint64_t delta) {
    uint64_t multiplier = 6364136223846793005ull, increment = increment_;
    uint64_t totalMultiplier = 1, totalIncrement = 0;
    while (delta > 0) {
      if (delta & 1u) {
        totalMultiplier *= multiplier;
        totalIncrement = totalIncrement * multiplier + increment;
      }
      increment = (multiplier + 1) * increment;
      multiplier *= multiplier;
      delta >>= 1u;
    }
    state_ = totalMultiplier * state_ + totalIncrement;
  }

  // Uniform in [0, 1), never 1.
  float uniform() { return unitFloatFromBits(nextUint()); }
  double uniformDouble() {
    uint64_t bits = (uint64_t(nextUint()) << 21) ^ uint64_t(nextUint() >> 11);
    return static_cast<double>(bits & ((1ull << 53) - 1)) * 0x1p-53;
  }
  Vec2f uniform2() {
    float a = uniform();
    return {a, uniform()};
  }
  // Uniform integer in [0, n).
  uint32_t uniformInt(uint32_t n) { return static_cast<uint32_t>((uint64_t(nextUint()) * n) >> 32); }

  uint64_t state() const { return state_; }
  uint64_t increment() const { return increment_; }
  void restore(uint64_t state, uint64_t increment) { state_ = state, increment_ = increment; }

 private:
  uint64_t state_ = 0;
  uint64_t increment_ = 1;
};

}  // namespace glint
