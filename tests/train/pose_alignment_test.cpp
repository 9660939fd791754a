// Direct image alignment of a camera: the warp's Jacobian against finite differences, the
// rotation formula, and a turned and shifted camera found again from an analytic scene.
#include "train/pose_alignment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "math/nearest_rotation.h"
#include "math/rng.h"

namespace glint {
namespace {

constexpr int kAlignWidth = 160, kAlignHeight = 120;

// A corner of three textured walls (x = 0, y = 0, z = 0, seen from the positive octant):
// depth varies across the view, so a turn and a shift look different.
double cornerDepth(const Ray& ray, Vec3d* hit) {
  double nearest = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    if (!(ray.direction[axis] < 0.0)) continue;
    const double t = -ray.origin[axis] / ray.direction[axis];
    const Vec3d p = ray.origin + ray.direction * t;
    bool inside = true;
    for (int other = 0; other < 3; ++other)
      if (other != axis && (p[other] < -1e-9 || p[other] > 3.0)) inside = false;
    if (inside && t > 0.0 && (nearest == 0.0 || t < nearest)) nearest = t, *hit = p;
  }
  return nearest;
}

// A smooth multi-scale texture of the position (linear radiance in [0.1, 0.9]).
Rgb texture(const Vec3d& p) {
  const double a = std::sin(7.0 * p.x + 3.0 * p.y) * std::cos(5.0 * p.z - 2.0 * p.x);
  const double b = std::sin(13.0 * p.y + 4.0 * p.z + 1.0) * std::sin(11.0 * p.x - 6.0 * p.z);
  return Rgb(float(0.5 + 0.25 * a + 0.15 * b), float(0.5 + 0.2 * b - 0.1 * a), float(0.5 + 0.3 * a * b));
}

// The corner seen from `camera` through pixel centres: colour and depth.
void renderCorner(const Camera& camera, Image* colour, Image* depth) {
  *colour = Image(camera.width, camera.height, 3);
  *depth = Image(camera.width, camera.height, 1);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Ray ray = camera.generateRay(x + 0.5, y + 0.5);
      Vec3d hit;
      const double t = cornerDepth(ray, &hit);
      if (t <= 0.0) continue;
      depth->at(x, y) = float(t);
      colour->setRgb(x, y, texture(hit));
    }
}

Camera cornerCamera() {
  return Camera::fromFieldOfView(Mat4::lookAt(Vec3d(2.6, 2.2, 1.9), Vec3d(0.6, 0.5, 0.4), Vec3d(0, 0, 1)), 1.0,
                                 kAlignWidth, kAlignHeight);
}

double angleBetweenDegrees(const Camera& a, const Camera& b) {
  return rotationAngleDegrees(a.rotation().transposed() * b.rotation());
}

TEST(PoseAlignment, WarpJacobianMatchesFiniteDifferences) {
  Rng rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3d q(rng.uniform() - 0.5, rng.uniform() - 0.5, -1.0 - 2.0 * rng.uniform());
    Vec2d pixel;
    double j[2][6];
    ASSERT_TRUE(projectWithPoseJacobian(q, 140.0, 138.0, 80.0, 60.0, &pixel, j));
    const double h = 1e-6;
    for (int k = 0; k < 6; ++k) {
      // The left increment q' = exp([w]x) q + v, by central differences in double.
      auto moved = [&](double s) {
        Vec3d w(0.0), v(0.0);
        (k < 3 ? w : v)[k % 3] = s;
        Vec2d p;
        double unused[2][6];
        EXPECT_TRUE(projectWithPoseJacobian(rotationFromVector(w) * q + v, 140.0, 138.0, 80.0, 60.0, &p, unused));
        return p;
      };
      const Vec2d plus = moved(h), minus = moved(-h);
      EXPECT_NEAR(j[0][k], (plus.x - minus.x) / (2 * h), 1e-5 * (1 + std::abs(j[0][k]))) << "u by parameter " << k;
      EXPECT_NEAR(j[1][k], (plus.y - minus.y) / (2 * h), 1e-5 * (1 + std::abs(j[1][k]))) << "v by parameter " << k;
    }
  }
}

TEST(PoseAlignment, RotationFromVectorIsARotationOfTheVectorsLength) {
  const Vec3d w(0.3, -0.2, 0.5);
  const Mat3d r = rotationFromVector(w);
  const Mat3d rtr = r.transposed() * r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(rtr.m[i][j], i == j ? 1.0 : 0.0, 1e-12);
  const Vec3d axis = r * w;  // the axis stays
  EXPECT_NEAR(length(axis - w), 0.0, 1e-12);
  const double cosine = (r.m[0].x + r.m[1].y + r.m[2].z - 1.0) * 0.5;
  EXPECT_NEAR(std::acos(cosine), length(w), 1e-12);
}

TEST(PoseAlignment, MovedCameraCarriesCameraCoordinatesByTheChange) {
  const Camera camera = cornerCamera();
  const Mat3d r = rotationFromVector(Vec3d(0.02, -0.01, 0.03));
  const Vec3d t(0.05, -0.02, 0.01);
  const Camera moved = movedCamera(camera, r, t);
  const Vec3d world(0.4, 0.9, 0.3);
  const Vec3d before = camera.cameraToWorld.inverse().transformPoint(world);
  const Vec3d after = moved.cameraToWorld.inverse().transformPoint(world);
  EXPECT_NEAR(length(after - (r * before + t)), 0.0, 1e-12);
}

// The target seen by the true camera, the render by one turned 1.5 degrees and moved 6 cm
// (a COLMAP camera's error at this size is about a degree): the alignment finds the true
// camera again.
TEST(PoseAlignment, FindsATurnedAndMovedCameraAgain) {
  const Camera truth = cornerCamera();
  const Camera wrong = movedCamera(truth, rotationFromVector(Vec3d(0.012, -0.018, 0.008)), Vec3d(0.04, -0.03, 0.03));
  ASSERT_GT(angleBetweenDegrees(truth, wrong), 1.3);
  Image target, unusedDepth, colour, depth;
  renderCorner(truth, &target, &unusedDepth);
  renderCorner(wrong, &colour, &depth);

  const PoseAlignment a = alignCameraPose(wrong, colour, depth, target);
  ASSERT_TRUE(a.accepted) << a.refusal;
  EXPECT_LT(angleBetweenDegrees(a.camera, truth), 0.03);
  EXPECT_LT(length(a.camera.position() - truth.position()), 0.003);
  // What stays is the points that leave the image or come into it at the borders.
  EXPECT_LT(a.costAfter, 0.25 * a.costBefore);
  EXPECT_GT(a.rotationDegrees, 1.3);
}

TEST(PoseAlignment, TheRightCameraStaysWhereItIs) {
  const Camera truth = cornerCamera();
  Image colour, depth;
  renderCorner(truth, &colour, &depth);
  const PoseAlignment a = alignCameraPose(truth, colour, depth, colour);
  EXPECT_FALSE(a.accepted);  // nothing to gain
  EXPECT_EQ(a.refusal, "the cost did not fall");
  EXPECT_EQ(a.camera.cameraToWorld.m, truth.cameraToWorld.m);
}

TEST(PoseAlignment, RefusesWithoutSurfacesOrBeyondItsBounds) {
  const Camera truth = cornerCamera();
  Image colour, depth;
  renderCorner(truth, &colour, &depth);
  Image empty(kAlignWidth, kAlignHeight, 1);
  PoseAlignment a = alignCameraPose(truth, colour, empty, colour);
  EXPECT_FALSE(a.accepted);
  EXPECT_NE(a.refusal.find("too few pixels"), std::string::npos);

  // A 1.5 degree error against a bound of 0.5.
  const Camera wrong = movedCamera(truth, rotationFromVector(Vec3d(0.012, -0.018, 0.008)), Vec3d(0.0, 0.0, 0.0));
  Image wrongColour, wrongDepth;
  renderCorner(wrong, &wrongColour, &wrongDepth);
  PoseAlignmentOptions tight;
  tight.maxRotationDegrees = 0.5;
  a = alignCameraPose(wrong, wrongColour, wrongDepth, colour, tight);
  EXPECT_FALSE(a.accepted);
  EXPECT_EQ(a.refusal, "a turn beyond the bound");
}

}  // namespace
}  // namespace glint
