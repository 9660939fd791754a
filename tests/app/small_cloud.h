// A small cloud of Gaussians around the origin of builtin:spheres, for command-line tests
// that need a scene to render.
#pragma once

#include <cmath>
#include <filesystem>

#include "scene/gaussian_ply.h"

namespace glint::test {

inline void writeSmallCloud(const std::filesystem::path& path) {
  GaussianScene scene;
  scene.resize(60);
  for (size_t i = 0; i < scene.size(); ++i) {
    scene.position[i] = {0.1f * float(i % 7) - 0.3f, 0.6f + 0.05f * float(i % 5), 0.08f * float(i % 3)};
    scene.logScale[i] = Vec3f(std::log(0.2f));
    scene.opacityLogit[i] = 1.0f;
    scene.diffuse[i] = {0.5f, 0.4f, 0.3f};
    scene.normal[i] = {0, 1, 0};
  }
  writeGaussianPly(path, scene);
}

}  // namespace glint::test
