// A textured corner of three walls (x = 0, y = 0, z = 0) tiled by flat Gaussians, cameras
// around it, and those cameras disturbed the way structure from motion errs: a scene whose
// depth varies across every view, for the tests of camera alignment.
#pragma once

#include <cmath>
#include <numbers>

#include "math/quat.h"
#include "scene/camera.h"
#include "scene/gaussians.h"
#include "train/pose_alignment.h"

namespace glint::test {

constexpr int kCornerWidth = 96, kCornerHeight = 72;

// A smooth texture of the position (linear radiance in [0.1, 0.9]).
inline Rgb cornerTexture(const Vec3d& p) {
  const double a = std::sin(4.0 * p.x + 2.0 * p.y) * std::cos(3.0 * p.z - 1.5 * p.x);
  const double b = std::sin(6.0 * p.y + 2.5 * p.z + 1.0) * std::sin(5.0 * p.x - 3.0 * p.z);
  return Rgb(float(0.5 + 0.25 * a + 0.15 * b), float(0.5 + 0.2 * b - 0.1 * a), float(0.5 + 0.3 * a * b));
}

// Three textured walls x = 0, y = 0, z = 0 over [0, 2]^2, tiled by flat, nearly opaque
// Gaussians: a corner whose depth varies across every view.
inline GaussianScene cornerScene() {
  constexpr int kSide = 50;
  constexpr double kSpacing = 2.0 / kSide;
  const double h = std::sqrt(0.5);
  const Quatf facing[3] = {Quatf{float(h), 0.0f, float(h), 0.0f},   // local z to +x
                           Quatf{float(h), float(-h), 0.0f, 0.0f},  // local z to +y
                           Quatf{1.0f, 0.0f, 0.0f, 0.0f}};         // local z is +z
  GaussianScene scene;
  scene.resize(3 * kSide * kSide);
  size_t i = 0;
  for (int wall = 0; wall < 3; ++wall)
    for (int a = 0; a < kSide; ++a)
      for (int b = 0; b < kSide; ++b, ++i) {
        Vec3d p(0.0);
        p[(wall + 1) % 3] = (a + 0.5) * kSpacing;
        p[(wall + 2) % 3] = (b + 0.5) * kSpacing;
        scene.position[i] = Vec3f(p);
        scene.rotation[i] = facing[wall];
        scene.logScale[i] = Vec3f(float(std::log(0.7 * kSpacing)), float(std::log(0.7 * kSpacing)), std::log(0.002f));
        scene.opacityLogit[i] = 5.0f;
        scene.diffuse[i] = cornerTexture(p);
        Vec3f n(0.0f);
        n[wall] = 1.0f;
        scene.normal[i] = n;
      }
  return scene;
}

constexpr int kCornerViews = 6;

inline Camera cornerCamera(int view) {
  const double angle = 0.2 + 0.24 * view;
  const Vec3d eye(3.2 * std::cos(angle), 3.2 * std::sin(angle), 2.4);
  return Camera::fromFieldOfView(Mat4::lookAt(eye, Vec3d(0.5, 0.5, 0.4), Vec3d(0, 0, 1)), 1.0, kCornerWidth, kCornerHeight);
}

// The camera turned by `degrees` and moved by `distance`, in directions that change from view
// to view and alternate in sign, so that the views share little motion: a structure-from-motion
// frame is the one its own cameras agree on.
inline Camera disturbed(const Camera& camera, double degrees, double distance, int view) {
  const double sign = view % 2 == 0 ? 1.0 : -1.0;
  const double radians = sign * degrees * std::numbers::pi / 180.0;
  const Vec3d axis = normalize(Vec3d(1.0, -0.6 + 0.3 * view, 0.4 - 0.2 * view));
  return movedCamera(camera, rotationFromVector(axis * radians),
                     normalize(Vec3d(-0.3, 0.8, 0.2 * view - 0.5)) * (sign * distance));
}

}  // namespace glint::test
