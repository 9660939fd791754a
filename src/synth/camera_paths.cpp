// Orbit camera paths.
#include "synth/camera_paths.h"

#include <cmath>

#include "math/sampling.h"

namespace glint {

std::vector<Mat4> orbitCameras(const OrbitPath& path, int count) {
  std::vector<Mat4> cameras;
  cameras.reserve(count);
  bool fullTurn = path.turns >= 1.0f;
  for (int i = 0; i < count; ++i) {
    double t = fullTurn ? double(i) / count : (count > 1 ? double(i) / (count - 1) : 0.5);
    double angle = path.phase + 2.0 * kPi * path.turns * t;
    double wave = 0.5 - 0.5 * std::cos(2.0 * kPi * path.heightWaves * t);
    double height = path.heightLow + (path.heightHigh - path.heightLow) * wave;
    Vec3d eye = Vec3d(path.center) + Vec3d(path.radius * std::cos(angle), height, path.radius * std::sin(angle));
    cameras.push_back(Mat4::lookAt(eye, Vec3d(path.target), Vec3d(0, 1, 0)));
  }
  return cameras;
}

CameraRig defaultCameraRig(const Vec3f& lower, const Vec3f& upper, float fovX) {
  CameraRig rig;
  rig.fovX = fovX;
  Vec3f centre = (lower + upper) * 0.5f;
  float radius = std::max(1e-3f, 0.5f * length(upper - lower));
  // Distance at which the bounding sphere fits the vertical field of view (4:3 images).
  float fovY = 2.0f * std::atan(std::tan(0.5f * fovX) * 0.75f);
  float distance = radius / std::sin(0.5f * std::min(fovX, fovY)) * 1.05f;
  rig.train = {centre, centre, distance, 0.15f * distance, 0.6f * distance, 0.0f, 1.0f, 2.0f};
  rig.test = {centre, centre, 0.9f * distance, 0.3f * distance, 0.45f * distance, 0.37f, 1.0f, 1.0f};
  return rig;
}

CameraRig sceneCameraRig(const MeshScene& scene) {
  if (scene.hasCameraRig) return scene.cameras;
  Vec3f lower, upper;
  scene.bounds(&lower, &upper);
  return defaultCameraRig(lower, upper, scene.cameras.fovX);
}

}  // namespace glint
