// One training pixel's targets in 18 bytes instead of 68: shared-exponent radiance, half
// depth, octahedral normal, 8-bit roughness and F0, so that 200 views of 1152x768 fit in
// memory with room to spare (docs/architecture.md, "Training targets in memory").
#pragma once

#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "math/vec.h"

namespace glint {

// RGB in one 32-bit word: three 9-bit mantissas sharing a 5-bit exponent (the layout of
// OpenGL's RGB9_E5). Each channel keeps 9 bits relative to the largest one, below the noise
// of any radiance target; values are clamped to [0, kMaxSharedExponentValue].
constexpr int kSharedMantissaBits = 9;
constexpr int kSharedExponentBias = 15;
constexpr float kMaxSharedExponentValue = 65408.0f;  // (511/512) * 2^16
// Below 2^-16 (the smallest exponent) the error is absolute: half a step of 2^-24.
constexpr float kSmallestSharedExponentError = 1.0f / 33554432.0f;  // 2^-25

inline uint32_t packSharedExponent(const Rgb& c) {
  auto clampChannel = [](float v) { return std::clamp(std::isfinite(v) ? v : 0.0f, 0.0f, kMaxSharedExponentValue); };
  const float r = clampChannel(c.x), g = clampChannel(c.y), b = clampChannel(c.z);
  const float largest = std::max({r, g, b});
  if (largest <= 0.0f) return 0;
  // The exponent that puts the largest channel's mantissa in [256, 512).
  int exponent = std::max(-kSharedExponentBias - 1, int(std::floor(std::log2(largest)))) + 1 + kSharedExponentBias;
  float step = std::ldexp(1.0f, exponent - kSharedExponentBias - kSharedMantissaBits);
  if (int(std::floor(largest / step + 0.5f)) == (1 << kSharedMantissaBits)) step *= 2.0f, ++exponent;
  auto mantissa = [&](float v) { return uint32_t(std::min(511.0f, std::floor(v / step + 0.5f))); };
  return mantissa(r) | (mantissa(g) << 9) | (mantissa(b) << 18) | (uint32_t(exponent) << 27);
}

inline Rgb unpackSharedExponent(uint32_t packed) {
  const float step = std::ldexp(1.0f, int(packed >> 27) - kSharedExponentBias - kSharedMantissaBits);
  return {float(packed & 511u) * step, float((packed >> 9) & 511u) * step, float((packed >> 18) & 511u) * step};
}

// A unit vector as two 16-bit coordinates of the octahedron |x| + |y| + |z| = 1 unfolded
// onto a square: under 0.05 degrees of error anywhere on the sphere.
inline uint32_t packOctahedral(const Vec3f& n) {
  const float l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  if (!(l1 > 0.0f)) return packOctahedral(Vec3f(0.0f, 0.0f, 1.0f));
  float u = n.x / l1, v = n.y / l1;
  if (n.z < 0.0f) {  // the lower half folds over the square's diagonals
    const float fu = (1.0f - std::abs(v)) * (u >= 0.0f ? 1.0f : -1.0f);
    const float fv = (1.0f - std::abs(u)) * (v >= 0.0f ? 1.0f : -1.0f);
    u = fu, v = fv;
  }
  auto quantise = [](float x) { return uint32_t(std::lround((std::clamp(x, -1.0f, 1.0f) * 0.5f + 0.5f) * 65535.0f)); };
  return quantise(u) | (quantise(v) << 16);
}

inline Vec3f unpackOctahedral(uint32_t packed) {
  const float u = float(packed & 0xffffu) / 65535.0f * 2.0f - 1.0f;
  const float v = float(packed >> 16) / 65535.0f * 2.0f - 1.0f;
  Vec3f n(u, v, 1.0f - std::abs(u) - std::abs(v));
  if (n.z < 0.0f) {
    n.x = (1.0f - std::abs(v)) * (u >= 0.0f ? 1.0f : -1.0f);
    n.y = (1.0f - std::abs(u)) * (v >= 0.0f ? 1.0f : -1.0f);
  }
  return normalize(n);
}

inline uint8_t packUnorm8(float v) {
  return uint8_t(std::lround(std::clamp(std::isfinite(v) ? v : 0.0f, 0.0f, 1.0f) * 255.0f));
}
inline float unpackUnorm8(uint8_t v) { return float(v) / 255.0f; }

// Depth as a half float: 11 significant bits (0.5 mm at 1 m). 0 stands for "no surface", as
// do depths beyond half's range; a surface at depth 0 is kept as the smallest depth.
inline uint16_t packDepth(float depth, bool surface) {
  if (!surface || !(depth < 65504.0f)) return 0;
  return Imath::half(std::max(depth, 1e-4f)).bits();
}
inline float unpackDepth(uint16_t bits) {
  Imath::half h;
  h.setBits(bits);
  return float(h);
}

// Packed without padding (18 bytes, not 20): x86 and ARM read unaligned words at full
// speed, and the targets are most of a large run's memory.
struct __attribute__((packed)) PackedTarget {
  uint32_t diffuse = 0;   // packSharedExponent: the colour target (diffuse, or the final image)
  uint32_t specular = 0;  // packSharedExponent
  uint32_t normal = 0;    // packOctahedral
  uint16_t depth = 0;     // packDepth; 0: no surface
  uint8_t roughness = 0;  // packUnorm8
  uint8_t f0[3] = {0, 0, 0};
};
static_assert(sizeof(PackedTarget) == 18, "a packed target is 18 bytes");

}  // namespace glint
