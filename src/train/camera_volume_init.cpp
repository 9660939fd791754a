// Random initialisation in the cameras' shared view volume, with a background shell.
#include "train/camera_volume_init.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "math/rng.h"
#include "math/sampling.h"
#include "render/camera_path.h"
#include "train/far_field.h"

namespace glint {

namespace {

// The fraction of the cameras' mean distance from their target that the cube reaches out.
constexpr double kVolumeHalfEdge = 0.35;
// The shell's radius over the farthest camera's distance from the target: every camera
// sees the shell only behind the scene, never between itself and the scene.
constexpr double kShellRadius = 2.0;
// Dense enough that neighbouring shell Gaussians overlap into an opaque wall.
constexpr float kShellOpacity = 0.95f;

// n points spread evenly over a sphere (the Fibonacci spiral).
std::vector<Vec3f> sphereShell(const Vec3d& centre, double radius, int n) {
  std::vector<Vec3f> points;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), phi = golden * i;
    points.push_back(Vec3f(centre + Vec3d(r * std::cos(phi), r * std::sin(phi), z) * radius));
  }
  return points;
}

}  // namespace

DenseInit initInCameraVolume(const Dataset& dataset, const DenseInitSettings& settings) {
  const DatasetSplit& split = dataset.train();
  if (split.views.empty()) throw Error(dataset.root().string(), "has no training views to initialise from");
  std::vector<Mat4> cameras;
  int64_t pixels = 0;
  for (const DatasetView& view : split.views) {
    cameras.push_back(view.camera.cameraToWorld);
    pixels += int64_t(view.camera.width) * view.camera.height;
  }
  const Vec3d target = cameraRing(cameras).target;
  double meanDistance = 0, farthest = 0;
  for (const Mat4& c : cameras) {
    const double d = length(c.column(3) - target);
    meanDistance += d / double(cameras.size());
    farthest = std::max(farthest, d);
  }
  if (!(meanDistance > 0))
    throw Error(dataset.root().string(), "every training camera stands at the point they look at: no volume to "
                                         "initialise");

  const int64_t count = std::clamp<int64_t>(pixels / kPixelsPerVolumeGaussian, 1000, kMaxVolumeGaussians);
  const double halfEdge = kVolumeHalfEdge * meanDistance;
  Rng rng = Rng::forKeys({0x63616d2d766f6c75ull});  // "cam-volu"
  ColouredPoints points;
  for (int64_t i = 0; i < count; ++i) {
    const Vec3d u(rng.uniform(), rng.uniform(), rng.uniform());
    points.positions.push_back(Vec3f(target + (u * 2.0 - Vec3d(1.0)) * halfEdge));
    points.colours.push_back(Rgb(0.5f));
  }
  DenseInit result;
  result.stats.source = InitSource::CameraVolume;
  result.stats.pointsUnprojected = count;
  result.stats.sceneExtent = float(meanDistance);
  // The spacing of the random points: the scale of a point without neighbours.
  const float spacing = float(2.0 * halfEdge / std::cbrt(double(count)));
  result.scene = gaussiansAtPoints(points, settings, spacing);

  const CaptureSource* source = dataset.capture();
  if (source && source->alphaBackground && source->alphaBackground->x + source->alphaBackground->y +
                                                   source->alphaBackground->z > 0.0f) {
    FarFieldSettings shell;
    shell.opacity = kShellOpacity;
    shell.diffuse = source->alphaBackground->x;  // white: the shell is grey-level, like the backgrounds offered
    const double radius = kShellRadius * farthest;
    GaussianScene wall = farFieldAtPoints(sphereShell(target, radius, kShellGaussians), shell, float(radius));
    for (size_t i = 0; i < wall.size(); ++i) result.scene.append(wall, i);
    result.stats.shellGaussians = int64_t(wall.size());
  }
  return result;
}

}  // namespace glint
