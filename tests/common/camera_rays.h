// Jittered pinhole camera rays for the tracer tests (seeded).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "math/rng.h"
#include "raytrace/gaussian_tracer.h"

namespace glint::test {

// width x height pinhole rays from eye towards target (60 degrees), jittered in the pixel.
inline std::vector<TraceRay> cameraRays(Vec3f eye, Vec3f target, int width, int height, uint64_t seed,
                                        float tMin = 0.0f) {
  Rng rng(seed);
  Vec3f forward = normalize(target - eye);
  Vec3f right = normalize(cross(forward, Vec3f(0, 1, 0)));
  Vec3f up = cross(right, forward);
  float focal = 0.5f * float(width) / std::tan(0.5f * 60.0f * 3.14159265f / 180.0f);
  std::vector<TraceRay> rays;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      float x = (float(i) + rng.uniform() - 0.5f * float(width)) / focal;
      float y = -(float(j) + rng.uniform() - 0.5f * float(height)) / focal;
      rays.push_back({eye, normalize(forward + right * x + up * y), tMin});
    }
  return rays;
}

}  // namespace glint::test
