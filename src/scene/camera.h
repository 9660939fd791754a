// Pinhole cameras: OpenGL camera axes (x right, y up, looking down -z), focal lengths fx, fy
// and principal point cx, cy in pixels (docs/data-format.md, "Cameras").
#pragma once

#include "core/cpu_gpu.h"
#include "math/mat3.h"
#include "math/mat4.h"
#include "math/vec.h"

namespace glint {

struct Ray {
  Vec3d origin;
  Vec3d direction;  // unit length
};

struct Camera {
  Mat4 cameraToWorld = Mat4::identity();  // x right, y up, camera looks down -z
  int width = 0;
  int height = 0;
  double fx = 0, fy = 0;  // focal lengths in pixels (fx = fy: square pixels)
  double cx = 0, cy = 0;  // principal point in pixels from the image's top-left corner

  // The NeRF/Blender camera: horizontal field of view fovX (radians), square pixels, the
  // principal point at the image centre.
  static Camera fromFieldOfView(const Mat4& cameraToWorld, double fovX, int width, int height);
  // Horizontal field of view of a camera whose principal point is at the image centre.
  double fieldOfViewX() const;
  // The same camera rendering newWidth x newHeight pixels: the focal lengths scale with the
  // width (so the horizontal field of view and the pixels' aspect stay), the principal point
  // keeps its relative position. A resize that keeps the aspect ratio is exact.
  Camera resized(int newWidth, int newHeight) const;

  // Ray through the continuous pixel position (px, py), px in [0, width) from the left,
  // py in [0, height) from the top: the pixel (i, j) has its centre at (i + 0.5, j + 0.5).
  // In camera space the direction is ((px - cx)/fx, -(py - cy)/fy, -1), normalised.
  GLINT_CPU_GPU Ray generateRay(double px, double py) const {
    Vec3d local((px - cx) / fx, -(py - cy) / fy, -1.0);
    Ray ray;
    ray.origin = cameraToWorld.column(3);
    ray.direction = normalize(cameraToWorld.transformVector(local));
    return ray;
  }
  Vec3d position() const { return cameraToWorld.column(3); }
  // The camera-to-world rotation (OpenGL camera axes).
  Mat3d rotation() const {
    Mat3d r;
    for (int i = 0; i < 3; ++i) r.m[i] = {cameraToWorld.m[i][0], cameraToWorld.m[i][1], cameraToWorld.m[i][2]};
    return r;
  }
  // generateRay inverted: the continuous pixel position p projects to, given the inverse of
  // cameraToWorld; false when p is not in front of the camera or projects outside the image
  // (every caller wants a pixel of the image).
  bool project(const Mat4& worldToCamera, const Vec3d& p, Vec2d* pixel) const;
  Vec3d forward() const { return normalize(-cameraToWorld.column(2)); }
};

}  // namespace glint
