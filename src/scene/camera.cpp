// Pinhole camera ray generation and projection.
#include "scene/camera.h"

#include <cmath>

namespace glint {

Camera Camera::fromFieldOfView(const Mat4& cameraToWorld, double fovX, int width, int height) {
  Camera camera;
  camera.cameraToWorld = cameraToWorld;
  camera.width = width;
  camera.height = height;
  camera.fx = camera.fy = 0.5 * double(width) / std::tan(0.5 * fovX);
  camera.cx = 0.5 * double(width);
  camera.cy = 0.5 * double(height);
  return camera;
}

double Camera::fieldOfViewX() const { return 2.0 * std::atan(0.5 * double(width) / fx); }

Camera Camera::resized(int newWidth, int newHeight) const {
  if (newWidth == width && newHeight == height) return *this;
  Camera camera = *this;
  const double sx = double(newWidth) / double(width), sy = double(newHeight) / double(height);
  camera.width = newWidth;
  camera.height = newHeight;
  camera.fx = fx * sx;
  camera.fy = fy * sx;
  camera.cx = cx * sx;
  camera.cy = cy * sy;
  return camera;
}

bool Camera::project(const Mat4& worldToCamera, const Vec3d& p, Vec2d* pixel) const {
  // generateRay's camera-space direction ((px - cx)/fx, -(py - cy)/fy, -1), solved for (px, py).
  Vec3d local = worldToCamera.transformPoint(p);
  double ahead = -local.z;
  if (!(ahead > 0.0)) return false;
  *pixel = {cx + fx * local.x / ahead, cy - fy * local.y / ahead};
  return pixel->x >= 0.0 && pixel->x < double(width) && pixel->y >= 0.0 && pixel->y < double(height);
}

}  // namespace glint
