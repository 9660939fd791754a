// Camera spheres from the depth buffers and the culling of Gaussians inside them.
#include "train/camera_culling.h"

#include <algorithm>
#include <cstdint>
#include <limits>

#include "core/error.h"
#include "core/parallel.h"
#include "math/mat4.h"
#include "scene/buffers.h"
#include "scene/capture_dataset.h"

namespace glint {

std::optional<CameraSphere> cameraSphere(const Image& depth, const Camera& camera, float factor) {
  GLINT_CHECK(depth.channels == 1, "cameraSphere: depth must have one channel");
  float nearest = std::numeric_limits<float>::infinity();
  for (float d : depth.pixels)
    if (hasSurface(d)) nearest = std::min(nearest, d);
  if (nearest == std::numeric_limits<float>::infinity()) return std::nullopt;
  return CameraSphere{camera, double(factor) * double(nearest)};
}

double nearestPointInView(const Camera& camera, const std::vector<Vec3d>& points) {
  const Mat4 worldToCamera = camera.cameraToWorld.inverse();
  double nearest = std::numeric_limits<double>::infinity();
  Vec2d pixel;
  for (const Vec3d& p : points)
    if (camera.project(worldToCamera, p, &pixel)) nearest = std::min(nearest, length(p - camera.position()));
  return nearest;
}

std::vector<CameraSphere> cameraSpheres(const Dataset& dataset, const DatasetSplit& split, float factor) {
  if (!(factor > 0.0f)) throw Error("camera culling settings", "the sphere radius factor must be positive");
  std::vector<std::optional<CameraSphere>> perView(split.views.size());
  parallelFor(int64_t(split.views.size()), 1, [&](int64_t i) {
    // A capture's view without depth gets no sphere: nothing says how near its surfaces are.
    if (!dataset.findBufferFile(split.views[size_t(i)], Buffer::Depth)) return;
    Image depth = dataset.loadBuffer(split, size_t(i), Buffer::Depth);
    perView[size_t(i)] = cameraSphere(depth, split.camera(size_t(i)), factor);
    if (perView[size_t(i)] && dataset.capture())
      perView[size_t(i)]->radius = std::min(
          perView[size_t(i)]->radius, double(factor) * nearestPointInView(split.camera(size_t(i)), dataset.capture()->points));
  });
  std::vector<CameraSphere> spheres;
  for (const std::optional<CameraSphere>& sphere : perView)
    if (sphere) spheres.push_back(*sphere);
  return spheres;
}

namespace {

// The test of insideCullRegion with the camera's world-to-camera matrix precomputed.
bool insideRegion(const CameraSphere& sphere, const Mat4& worldToCamera, const Vec3d& p, CullRegion region) {
  const Camera& camera = sphere.camera;
  Vec3d d = p - camera.position();
  if (!(dot(d, d) < sphere.radius * sphere.radius)) return false;
  if (region == CullRegion::WholeSphere) return true;
  Vec2d pixel;
  return camera.project(worldToCamera, p, &pixel);
}

}  // namespace

bool insideCullRegion(const CameraSphere& sphere, const Vec3d& p, CullRegion region) {
  return insideRegion(sphere, sphere.camera.cameraToWorld.inverse(), p, region);
}

std::vector<bool> outsideCameraSpheres(const GaussianScene& scene, const std::vector<CameraSphere>& spheres,
                                       CullRegion region) {
  // Brute force: a hundred spheres against a few hundred thousand means is a few tens of
  // millions of distance tests, milliseconds once every few hundred steps. Bytes, not
  // std::vector<bool>, while threads write: neighbouring bits share a word.
  std::vector<Mat4> worldToCamera;
  for (const CameraSphere& sphere : spheres) worldToCamera.push_back(sphere.camera.cameraToWorld.inverse());
  std::vector<uint8_t> keep(scene.size(), 1);
  parallelFor(int64_t(scene.size()), 4096, [&](int64_t i) {
    Vec3d p(scene.position[size_t(i)]);
    for (size_t s = 0; s < spheres.size(); ++s)
      if (insideRegion(spheres[s], worldToCamera[s], p, region)) {
        keep[size_t(i)] = 0;
        break;
      }
  });
  return std::vector<bool>(keep.begin(), keep.end());
}

size_t cullInsideCameraSpheres(GaussianScene& scene, const std::vector<CameraSphere>& spheres, CullRegion region) {
  std::vector<bool> keep = outsideCameraSpheres(scene, spheres, region);
  size_t removed = size_t(std::count(keep.begin(), keep.end(), false));
  if (removed > 0) scene.filter(keep);
  return removed;
}

}  // namespace glint
