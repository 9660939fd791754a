// Pinhole cameras in the NeRF/Blender convention: OpenGL camera axes, principal point at
// the image centre, square pixels, horizontal field of view.
#pragma once

#include "math/mat4.h"
#include "math/vec.h"

namespace glint {

struct Ray {
  Vec3d origin;
  Vec3d direction;  // unit length
};

struct Camera {
  Mat4 cameraToWorld = Mat4::identity();  // x right, y up, camera looks down -z
  double fovX = 0.8;                      // horizontal field of view, radians
  int width = 0;
  int height = 0;

  // Focal length in pixels.
  double focal() const;
  // Ray through the continuous pixel position (px, py), px in [0, width) from the left,
  // py in [0, height) from the top: the pixel (i, j) has its centre at (i + 0.5, j + 0.5).
  // In camera space the direction is ((px - W/2)/f, -(py - H/2)/f, -1), normalised.
  Ray generateRay(double px, double py) const;
  Vec3d position() const { return cameraToWorld.column(3); }
  // generateRay inverted: the continuous pixel position p projects to, given the inverse of
  // cameraToWorld; false when p is not in front of the camera or projects outside the image
  // (every caller wants a pixel of the image).
  bool project(const Mat4& worldToCamera, const Vec3d& p, Vec2d* pixel) const;
  Vec3d forward() const { return normalize(-cameraToWorld.column(2)); }
};

}  // namespace glint
