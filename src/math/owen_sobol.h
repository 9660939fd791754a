// Stratified 2D samples: an Owen-scrambled, index-shuffled (0,2)-sequence per stream, so the
// samples of one pixel fill the square evenly instead of clumping like independent ones.
#pragma once

#include <cstdint>

#include "core/cpu_gpu.h"
#include "math/rng.h"
#include "math/vec.h"

namespace glint {

constexpr uint32_t reverseBits32(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

// The first two dimensions of Sobol's sequence, a (0,2)-sequence in base 2: every aligned
// block of 2^m consecutive indices puts exactly one point in each elementary interval of
// area 2^-m (2^a x 2^b cells, a + b = m). Values are 32-bit fixed-point fractions.
// Dimension 0 is the van der Corput sequence; dimension 1's direction numbers are
// v_1 = 1/2, v_{j+1} = v_j xor (v_j / 2) (the Pascal matrix mod 2).
constexpr uint32_t sobolDimension0(uint32_t index) { return reverseBits32(index); }
constexpr uint32_t sobolDimension1(uint32_t index) {
  uint32_t value = 0;
  for (uint32_t v = 1u << 31; index != 0; index >>= 1, v ^= v >> 1)
    if (index & 1u) value ^= v;
  return value;
}

// Nested uniform (Owen) scrambling of a 32-bit fraction by hashing (B. Burley, "Practical
// Hash-based Owen Scrambling", JCGT 2020, after Laine and Karras 2011): each bit is flipped
// by a hash of the bits above it, so a (0,m,2)-net stays a (0,m,2)-net while its points
// become uniformly random one by one.
constexpr uint32_t owenScramble(uint32_t x, uint32_t seed) {
  // In bit-reversed order, multiplying by an even constant makes each bit depend only on
  // the bits below it, i.e. (reversed back) on the more significant bits of x.
  x = reverseBits32(x);
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return reverseBits32(x);
}

// Sample `index` of the stratified stream named by streamKey (e.g. hashKeys({seed, view,
// pixel, dimension})). Samples [2^m k, 2^m (k+1)) of a stream form a (0,m,2)-net; for other
// counts the points are still well spread. Each sample on its own is uniform on [0,1)^2,
// so estimators stay unbiased whatever index they use. The index is shuffled by Owen-
// scrambling its bits (each flipped by a hash of the bits above it, so every aligned block
// of 2^m indices maps onto another such block, which is again a net), so that the streams
// of a path's dimensions pair their samples independently of each other.
GLINT_CPU_GPU inline Vec2f stratifiedSample2(uint64_t streamKey, uint32_t index) {
  const uint64_t seeds = mix64(streamKey);
  const uint32_t shuffled = owenScramble(index, uint32_t(streamKey));
  return {unitFloatFromBits(owenScramble(sobolDimension0(shuffled), uint32_t(seeds))),
          unitFloatFromBits(owenScramble(sobolDimension1(shuffled), uint32_t(seeds >> 32)))};
}

}  // namespace glint
