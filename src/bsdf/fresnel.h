// Schlick's approximation of the Fresnel reflectance, per colour channel.
#pragma once

#include <algorithm>

#include "core/cpu_gpu.h"
#include "math/vec.h"

namespace glint {

// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering", eq. 15:
// F = F0 + (1 - F0)(1 - cos)^5. cosTheta is the cosine between the viewing direction and
// the (micro)facet normal; it is clamped to [0, 1] so F stays within [F0, 1].
// Schlick's weight (1 - cos)^5, cos clamped to [0, 1]: F = F0 + (1 - F0) w, so
// dF / dF0 = 1 - w in each channel.
GLINT_CPU_GPU inline float schlickWeight(float cosTheta) {
  float m = 1.0f - std::clamp(cosTheta, 0.0f, 1.0f);
  float m2 = m * m;
  return m2 * m2 * m;
}

GLINT_CPU_GPU inline Rgb F_Schlick(const Rgb& F0, float cosTheta) {
  return F0 + (Rgb(1.0f) - F0) * schlickWeight(cosTheta);
}

}  // namespace glint
