// Direction helpers shared by the BSDF tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "math/rng.h"
#include "math/sampling.h"
#include "math/vec.h"

namespace glint::test {

constexpr double kPiD = std::numbers::pi;

// A unit direction at polar angle acos(cosTheta) and azimuth phi (z up).
inline Vec3f direction(double cosTheta, double phi) {
  double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
  return Vec3f(float(sinTheta * std::cos(phi)), float(sinTheta * std::sin(phi)), float(cosTheta));
}

// A uniform direction strictly above the horizon (z >= minZ).
inline Vec3f randomUpperDirection(Rng& rng, float minZ = 1e-4f) {
  Vec3f w = sampleUniformSphere(rng.uniform2());
  return Vec3f(w.x, w.y, std::max(std::abs(w.z), minZ));
}

}  // namespace glint::test
