// Random overlapping Gaussian clouds, directions and rays for the tracer tests (seeded).
#pragma once

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "math/rng.h"
#include "raytrace/gaussian_tracer.h"
#include "raytrace/trace_settings.h"
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

// Rays from outside the cloud towards it, from inside it (often inside Gaussians, with
// Gaussians behind the origin), and inside ones with tMin > 0 that cuts Gaussians.
inline std::vector<TraceRay> randomRays(size_t n, uint64_t seed) {
  Rng rng(seed);
  std::vector<TraceRay> rays(n);
  for (size_t i = 0; i < n; ++i) {
    TraceRay& ray = rays[i];
    switch (i % 3) {
      case 0: {
        ray.origin = randomDirection(rng) * 3.0f;
        Vec3f target(uniform(rng, -0.8f, 0.8f), uniform(rng, -0.8f, 0.8f), uniform(rng, -0.8f, 0.8f));
        ray.direction = normalize(target - ray.origin);
        break;
      }
      case 1:
        ray.origin = {uniform(rng, -0.9f, 0.9f), uniform(rng, -0.9f, 0.9f), uniform(rng, -0.9f, 0.9f)};
        ray.direction = randomDirection(rng);
        break;
      default:
        ray.origin = {uniform(rng, -0.9f, 0.9f), uniform(rng, -0.9f, 0.9f), uniform(rng, -0.9f, 0.9f)};
        ray.direction = randomDirection(rng);
        ray.tMin = uniform(rng, 0.0f, 0.5f);
        break;
    }
  }
  return rays;
}

// The tracer tests' settings: every given kernel power with minTransmittance 1e-4 and
// 0.01, each without and with the exact tail.
inline std::vector<TraceSettings> traceSettingsGrid(std::initializer_list<float> powers) {
  std::vector<TraceSettings> grid;
  for (float power : powers)
    for (float minT : {1e-4f, 0.01f})
      for (bool exactTail : {false, true}) {
        TraceSettings settings;
        settings.kernelPower = power;
        settings.minTransmittance = minT;
        settings.exactTail = exactTail;
        grid.push_back(settings);
      }
  return grid;
}

inline std::string describe(const TraceSettings& s) {
  return "p=" + std::to_string(s.kernelPower) + " minT=" + std::to_string(s.minTransmittance) +
         (s.exactTail ? " exact tail" : "");
}

}  // namespace glint
