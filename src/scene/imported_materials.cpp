// Imported material defaults: shortest-axis normals oriented away from the scene's centre.
#include "scene/imported_materials.h"

#include <algorithm>
#include <vector>

#include "math/mat3.h"

namespace glint {

Vec3f shortestAxis(const Quatf& rotation, const Vec3f& logScale) {
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (logScale[k] < logScale[axis]) axis = k;
  }
  return normalize(quatToRotation(rotation).column(axis));
}

Vec3f medianPosition(const GaussianScene& scene) {
  if (scene.empty()) return Vec3f(0.0f);
  Vec3f centre;
  std::vector<float> values(scene.size());
  for (int k = 0; k < 3; ++k) {
    for (size_t i = 0; i < scene.size(); ++i) values[i] = scene.position[i][k];
    auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    centre[k] = *middle;
  }
  return centre;
}

void setShortestAxisNormals(GaussianScene& scene, const Vec3f& centre) {
  for (size_t i = 0; i < scene.size(); ++i) {
    Vec3f n = shortestAxis(scene.rotation[i], scene.logScale[i]);
    scene.normal[i] = dot(n, scene.position[i] - centre) < 0.0f ? -n : n;
  }
}

}  // namespace glint
