// Pinhole camera ray generation.
#include "scene/camera.h"

#include <cmath>

namespace glint {

double Camera::focal() const { return 0.5 * double(width) / std::tan(0.5 * fovX); }

Ray Camera::generateRay(double px, double py) const {
  double f = focal();
  Vec3d local((px - 0.5 * width) / f, -(py - 0.5 * height) / f, -1.0);
  Ray ray;
  ray.origin = cameraToWorld.column(3);
  ray.direction = normalize(cameraToWorld.transformVector(local));
  return ray;
}

bool Camera::project(const Mat4& worldToCamera, const Vec3d& p, Vec2d* pixel) const {
  // The camera-space direction of the ray through (px, py) is ((px - W/2)/f, -(py - H/2)/f, -1).
  Vec3d local = worldToCamera.transformPoint(p);
  double ahead = -local.z;
  if (!(ahead > 0.0)) return false;
  double f = focal();
  *pixel = {0.5 * width + f * local.x / ahead, 0.5 * height - f * local.y / ahead};
  return pixel->x >= 0.0 && pixel->x < double(width) && pixel->y >= 0.0 && pixel->y < double(height);
}

}  // namespace glint
