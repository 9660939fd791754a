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

}  // namespace glint
