// Random overlapping Gaussian clouds and directions for the tracer tests (seeded).
#pragma once

#include <cmath>
#include <cstdint>

#include "math/rng.h"
#include "scene/gaussians.h"

namespace glint {

inline float uniform(Rng& rng, float a, float b) { return a + (b - a) * rng.uniform(); }

inline Vec3f randomDirection(Rng& rng) {
  for (;;) {
    Vec3f v(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    float n2 = dot(v, v);
    if (n2 > 1e-4f && n2 <= 1.0f) return v / std::sqrt(n2);
  }
}

inline Quatf randomRotation(Rng& rng) {
  for (;;) {
    Quatf q{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    float n = q.norm();
    if (n > 1e-2f && n <= 1.0f) return q;  // uniform on the sphere of rotations after normalising
  }
}

// n Gaussians in the box [-1, 1]^3 with random rotations, anisotropic log-scales that make
// them overlap heavily, opacities spread over (0, 1) and random attributes.
inline GaussianScene randomScene(size_t n, uint64_t seed) {
  Rng rng(seed);
  GaussianScene scene;
  scene.resize(n);
  for (size_t i = 0; i < n; ++i) {
    scene.position[i] = {uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    scene.rotation[i] = randomRotation(rng);
    scene.logScale[i] = {uniform(rng, -4.0f, -1.8f), uniform(rng, -4.0f, -1.8f), uniform(rng, -4.0f, -1.8f)};
    scene.opacityLogit[i] = logit(uniform(rng, 0.01f, 0.99f));
    scene.diffuse[i] = {rng.uniform(), rng.uniform(), rng.uniform()};
    scene.normal[i] = randomDirection(rng) * uniform(rng, 0.5f, 1.0f);
    scene.roughness[i] = rng.uniform();
    scene.f0[i] = {rng.uniform(), rng.uniform(), rng.uniform()};
  }
  return scene;
}

}  // namespace glint
