// Far-field Gaussians: a truncated normal cloud around the scene centre.
#include "train/far_field.h"

#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "raytrace/gaussian_kernel.h"
#include "math/rng.h"
#include "math/sampling.h"
#include "train/nearest_neighbours.h"
#include "train/training_views.h"

namespace glint {

void checkFarFieldSettings(const FarFieldSettings& s, const std::string& where) {
  if (s.count < 0 || s.count > kMaxFarFieldCount) throw Error(where, "far_field.count must be in [0, 10000000]");
  if (!(s.sigmaFactor > 0.0f && std::isfinite(s.sigmaFactor))) throw Error(where, "far_field.sigma_factor must be positive");
  if (!(s.truncation > 0.0f && std::isfinite(s.truncation))) throw Error(where, "far_field.truncation must be positive");
  if (!(s.opacity > 0.0f && s.opacity < 1.0f)) throw Error(where, "far_field.opacity must lie in (0, 1)");
  if (!(s.diffuse >= 0.0f && std::isfinite(s.diffuse))) throw Error(where, "far_field.diffuse must be 0 or more");
  if (s.neighbours < 1 || s.neighbours > 64) throw Error(where, "far_field.neighbours must be in [1, 64]");
  if (s.reflectionSeeds < 0 || s.reflectionSeeds > kMaxFarFieldCount)
    throw Error(where, "far_field.reflection_seeds must be in [0, 10000000]");
  if (!(s.reflectionSeedRoughness >= 0.0f && s.reflectionSeedRoughness <= 1.0f))
    throw Error(where, "far_field.reflection_seed_roughness must lie in [0, 1]");
  for (size_t b = 0; b < s.boxes.size(); ++b) {
    const FarFieldBox& box = s.boxes[b];
    const std::string name = "far_field.boxes[" + std::to_string(b) + "]";
    for (int axis = 0; axis < 3; ++axis)
      if (!(std::isfinite(box.min[axis]) && std::isfinite(box.max[axis]) && box.min[axis] < box.max[axis]))
        throw Error(where, name + ": min must be below max on every axis, and both finite");
    if (box.count < 1 || box.count > kMaxFarFieldCount) throw Error(where, name + ": count must be in [1, 10000000]");
  }
}

GaussianScene farFieldGaussians(const FarFieldSettings& s, const Vec3f& centre, float sceneRadius, uint64_t seed) {
  GLINT_CHECK(sceneRadius > 0.0f, "farFieldGaussians: the scene radius must be positive");
  const float sigma = s.sigmaFactor * sceneRadius;
  const float limit2 = s.truncation * s.truncation;
  // A Gaussian stream of its own, so that the cloud does not depend on anything else the
  // run draws.
  Rng rng = Rng::forKeys({seed, 0x6661722d6669656cull});  // "far-fiel"
  std::vector<Vec3f> points;
  size_t total = size_t(s.count);
  for (const FarFieldBox& box : s.boxes) total += size_t(box.count);
  points.reserve(total);
  while (points.size() < size_t(s.count)) {
    // Box-Muller pairs; rejection of the tail beyond the truncation radius.
    Vec3f z;
    for (int axis = 0; axis < 3; ++axis) {
      float u1 = std::max(rng.uniform(), 1e-12f), u2 = rng.uniform();
      z[axis] = std::sqrt(-2.0f * std::log(u1)) * std::cos(2.0f * kPi * u2);
    }
    if (dot(z, z) > limit2) continue;
    points.push_back(centre + z * sigma);
  }
  for (const FarFieldBox& box : s.boxes)
    for (int i = 0; i < box.count; ++i)
      points.push_back(box.min + Vec3f(rng.uniform(), rng.uniform(), rng.uniform()) * (box.max - box.min));
  return farFieldAtPoints(points, s, sceneRadius);
}

GaussianScene farFieldAtPoints(const std::vector<Vec3f>& points, const FarFieldSettings& s, float sceneRadius) {
  std::vector<float> spacing = meanNeighbourDistances(points, s.neighbours);
  GaussianScene scene;
  scene.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    scene.position[i] = points[i];
    scene.rotation[i] = Quatf{};
    scene.logScale[i] = Vec3f(std::log(std::max(spacing[i], 1e-4f * sceneRadius)));
    scene.opacityLogit[i] = logit(s.opacity);
    scene.diffuse[i] = Rgb(s.diffuse);
    scene.normal[i] = Vec3f(0.0f);
    scene.roughness[i] = 0.0f;
    scene.f0[i] = Rgb(0.04f);
  }
  return scene;
}

std::vector<Mat4> worldToCameras(const TrainingViews& views) {
  std::vector<Mat4> worldToCamera;
  for (size_t v = 0; v < views.viewCount(); ++v) worldToCamera.push_back(views.camera(v).cameraToWorld.inverse());
  return worldToCamera;
}

double gapBehindObservedSurfaces(const Vec3d& p, const TrainingViews& views, std::span<const Mat4> worldToCamera) {
  double gap = INFINITY;
  for (size_t v = 0; v < views.viewCount() && gap > 0.0; ++v) {
    const Camera& camera = views.camera(v);
    Vec2d pixel;
    if (!camera.project(worldToCamera[v], p, &pixel)) continue;
    const PixelTarget t = views.target(v, size_t(pixel.y) * size_t(camera.width) + size_t(pixel.x));
    if (!t.surface) continue;
    gap = std::min(gap, length(p - camera.position()) - double(t.depth));
  }
  return gap;
}

size_t carveObservedFreeSpace(GaussianScene* farField, const TrainingViews& views, const TraceSettings& trace) {
  // Without depth buffers no view records where its free space ends.
  if (!views.supervised().depth) return 0;
  GaussianScene& g = *farField;
  const std::vector<Mat4> worldToCamera = worldToCameras(views);
  std::vector<bool> keep(g.size(), true);
  parallelFor(int64_t(g.size()), 256, [&](int64_t i) {
    const double gap = gapBehindObservedSurfaces(Vec3d(g.position[i]), views, worldToCamera);
    if (!(gap > 0.0)) {
      keep[i] = false;
      return;
    }
    if (std::isinf(gap)) return;
    // Proxy radius in units of the scale: the support ends at proxyRadius x scale.
    const double support = proxyRadius(double(g.opacity(size_t(i))), trace);
    if (!(support > 0.0)) return;  // never reaches alpha_min: invisible at any size
    const float maxLogScale = float(std::log(gap / support));
    Vec3f& s = g.logScale[i];
    s = {std::min(s.x, maxLogScale), std::min(s.y, maxLogScale), std::min(s.z, maxLogScale)};
  });
  const size_t before = g.size();
  g.filter(keep);
  return before - g.size();
}

}  // namespace glint
