// The filmic tonemap used for 8-bit images (docs/data-format.md), and its closed-form inverse.
#pragma once

#include <algorithm>
#include <cmath>

#include "math/vec.h"

namespace glint {

// y = (x (6.2 x + 0.5) / (x (6.2 x + 1.7) + 0.06))^1.3 for x >= 0: a Hejl-Burgess-Dawson
// style filmic curve raised to 1.3 (the paper's published data uses it for 8-bit images).
// Evaluated in double: in float, rounding noise near y = 1 exceeds the curve's slope and the
// result stops being monotonic (x around 10 and above).
inline float tonemapFilmic(float x) {
  double d = std::max(0.0, double(x));
  double y = (d * (6.2 * d + 0.5)) / (d * (6.2 * d + 1.7) + 0.06);
  return static_cast<float>(std::pow(y, 1.3));
}

// Inverse of tonemapFilmic for y in [0, 1): solve the quadratic of the rational part for x
// after undoing the power (constants from docs/data-format.md). y >= 1 maps to +infinity, so
// the result is capped at kMaxUntonemapped: tonemapFilmic(128) = 254.5 / 255, so every
// radiance above it is stored as 8-bit white, and a saturated pixel decodes to this
// smallest value consistent with it rather than to an arbitrarily huge target.
constexpr float kMaxUntonemapped = 128.0f;
inline float untonemapFilmic(float y) {
  if (y <= 0.0f) return 0.0f;
  // Work in double: near y' = 1 the denominator cancels.
  double yp = std::pow(double(std::min(y, 1.0f)), 1.0 / 1.3);
  if (yp >= 1.0) return kMaxUntonemapped;
  double x = (0.1371 * yp + 0.09549 * std::sqrt(yp * yp - 0.1512 * yp + 0.1783) - 0.04032) / (1.0 - yp);
  return static_cast<float>(std::clamp(x, 0.0, double(kMaxUntonemapped)));
}

inline Rgb tonemapFilmic(const Rgb& c) { return {tonemapFilmic(c.x), tonemapFilmic(c.y), tonemapFilmic(c.z)}; }
inline Rgb untonemapFilmic(const Rgb& c) { return {untonemapFilmic(c.x), untonemapFilmic(c.y), untonemapFilmic(c.z)}; }

}  // namespace glint
