// A generated scene of surface Gaussians for the benchmarks: a checker floor and three
// spheres (chrome, gold, rough plastic), so paths reflect as on a real capture's surfaces.
#pragma once

#include <cmath>
#include <cstdint>

#include "math/rng.h"
#include "scene/gaussians.h"

namespace glint {

// A flat Gaussian at p facing n (its thin axis along n).
inline void addSurfel(GaussianScene& scene, size_t i, Vec3f p, Vec3f n, float size, Rgb diffuse, float roughness, Rgb f0) {
  scene.position[i] = p;
  // Rotation taking local z to n (half-way quaternion; n = -z turns about x).
  Vec3f z(0, 0, 1), axis = cross(z, n);
  float w = 1.0f + dot(z, n);
  scene.rotation[i] = w < 1e-6f ? Quatf(0, 1, 0, 0) : Quatf(w, axis.x, axis.y, axis.z);
  scene.logScale[i] = Vec3f(std::log(size), std::log(size), std::log(size * 0.1f));
  scene.opacityLogit[i] = logit(0.95f);
  scene.diffuse[i] = diffuse;
  scene.normal[i] = n;
  scene.roughness[i] = roughness;
  scene.f0[i] = f0;
}

inline GaussianScene makeSurfaceScene(size_t n, uint64_t seed) {
  Rng rng(seed);
  GaussianScene scene;
  scene.resize(n);
  const Vec3f centers[3] = {{-1.3f, 0.6f, 0.0f}, {0.0f, 0.6f, -0.8f}, {1.3f, 0.6f, 0.0f}};
  const float radius = 0.6f;
  size_t floorCount = n / 2;
  for (size_t i = 0; i < n; ++i) {
    if (i < floorCount) {  // a 6 x 6 m checker floor
      Vec3f p(rng.uniform() * 6 - 3, 0, rng.uniform() * 6 - 3);
      bool dark = (int(std::floor(p.x * 2)) + int(std::floor(p.z * 2))) & 1;
      addSurfel(scene, i, p, {0, 1, 0}, 0.03f, Rgb(dark ? 0.1f : 0.7f), 0.5f, Rgb(0.04f));
    } else {  // three spheres: chrome, gold, rough plastic
      int s = int(i % 3);
      float zc = rng.uniform() * 2 - 1, phi = 6.2831853f * rng.uniform();
      float r = std::sqrt(std::max(0.0f, 1 - zc * zc));
      Vec3f dir(r * std::cos(phi), zc, r * std::sin(phi));
      Rgb f0 = s == 0 ? Rgb(0.95f) : s == 1 ? Rgb(1.0f, 0.77f, 0.34f) : Rgb(0.04f);
      addSurfel(scene, i, centers[s] + dir * radius, dir, 0.025f, Rgb(s == 2 ? 0.6f : 0.05f),
                s == 0 ? 0.05f : s == 1 ? 0.3f : 0.8f, f0);
    }
  }
  return scene;
}

}  // namespace glint
