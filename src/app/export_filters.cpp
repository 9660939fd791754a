// Export filters: the far-field distance cut and the crop box, as masks for GaussianScene::filter.
#include "app/export_filters.h"

#include <algorithm>

namespace glint {

std::vector<bool> nearTheCameras(const GaussianScene& scene, const SceneSphere& cameras, float radiusFactor) {
  const double radius = double(radiusFactor) * double(cameras.radius);
  std::vector<bool> keep(scene.size());
  for (size_t i = 0; i < scene.size(); ++i) keep[i] = length(Vec3d(scene.position[i]) - cameras.centre) <= radius;
  return keep;
}

std::vector<bool> insideBox(const GaussianScene& scene, const WorldBox& box) {
  std::vector<bool> keep(scene.size());
  for (size_t i = 0; i < scene.size(); ++i) keep[i] = box.contains(Vec3d(scene.position[i]));
  return keep;
}

size_t countDropped(const std::vector<bool>& keep) { return size_t(std::count(keep.begin(), keep.end(), false)); }

}  // namespace glint
