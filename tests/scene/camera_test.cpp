// Pinhole rays against the NeRF/Blender formula, for hand-made and dataset cameras.
#include "scene/camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/temp_folder.h"
#include "scene/dataset.h"
#include "scene/synthetic_dataset.h"

namespace glint {
namespace {

// Direction through the centre of pixel (i, j) of a camera with horizontal field of view fovX:
// x = (i + 0.5 - W/2)/f, y = -(j + 0.5 - H/2)/f, z = -1 in camera space with f = W / (2 tan(fovX/2)),
// mapped by the camera-to-world rotation.
Vec3d expectedDirection(const Camera& camera, double fovX, int i, int j) {
  double f = 0.5 * camera.width / std::tan(0.5 * fovX);
  Vec3d local((i + 0.5 - 0.5 * camera.width) / f, -(j + 0.5 - 0.5 * camera.height) / f, -1.0);
  const auto& m = camera.cameraToWorld.m;
  Vec3d world(m[0][0] * local.x + m[0][1] * local.y + m[0][2] * local.z,
              m[1][0] * local.x + m[1][1] * local.y + m[1][2] * local.z,
              m[2][0] * local.x + m[2][1] * local.y + m[2][2] * local.z);
  return normalize(world);
}

void expectRaysMatchFormula(const Camera& camera, double fovX) {
  Vec3d origin(camera.cameraToWorld.m[0][3], camera.cameraToWorld.m[1][3], camera.cameraToWorld.m[2][3]);
  for (int j = 0; j < camera.height; ++j)
    for (int i = 0; i < camera.width; ++i) {
      Ray ray = camera.generateRay(i + 0.5, j + 0.5);
      Vec3d expected = expectedDirection(camera, fovX, i, j);
      EXPECT_NEAR(length(ray.direction), 1.0, 1e-12);
      EXPECT_NEAR(length(ray.direction - expected), 0.0, 1e-12) << "pixel " << i << ", " << j;
      EXPECT_NEAR(length(ray.origin - origin), 0.0, 1e-12);
    }
}

TEST(Camera, FocalLengthFromHorizontalFieldOfView) {
  // tan(fov/2) = 0.5 -> f = W, square pixels, principal point at the centre.
  Camera camera = Camera::fromFieldOfView(Mat4::identity(), 2.0 * std::atan(0.5), 800, 600);
  EXPECT_NEAR(camera.fx, 800.0, 1e-9);
  EXPECT_NEAR(camera.fy, 800.0, 1e-9);
  EXPECT_DOUBLE_EQ(camera.cx, 400.0);
  EXPECT_DOUBLE_EQ(camera.cy, 300.0);
  EXPECT_NEAR(camera.fieldOfViewX(), 2.0 * std::atan(0.5), 1e-12);
}

TEST(Camera, RaysThroughPixelCentresFollowTheNerfFormula) {
  Camera camera =
      Camera::fromFieldOfView(Mat4::lookAt(Vec3d(1, -3, 2), Vec3d(0, 0, 0.5), Vec3d(0, 0, 1)), 0.7, 8, 6);
  expectRaysMatchFormula(camera, 0.7);
  // The image centre looks along -z of the camera, i.e. forward().
  Ray centre = camera.generateRay(4.0, 3.0);
  EXPECT_NEAR(length(centre.direction - camera.forward()), 0.0, 1e-12);
  // Image x grows to the camera's right, image y downwards (OpenGL y is up).
  Vec3d right = camera.cameraToWorld.column(0), up = camera.cameraToWorld.column(1);
  EXPECT_GT(dot(camera.generateRay(7.5, 3.0).direction, right), 0.0);
  EXPECT_LT(dot(camera.generateRay(4.0, 5.5).direction, up), 0.0);
}

TEST(Camera, DatasetCamerasUseTheSplitsFieldOfViewAndImageSize) {
  test::TempFolder folder;
  test::SyntheticDataset written = test::writeSyntheticDataset(folder.path());
  Dataset dataset = Dataset::open(folder.path());
  for (size_t v = 0; v < dataset.train().views.size(); ++v) {
    Camera camera = dataset.train().camera(v);
    EXPECT_EQ(camera.width, test::kSyntheticWidth);
    EXPECT_EQ(camera.height, test::kSyntheticHeight);
    EXPECT_NEAR(camera.fieldOfViewX(), 0.7, 1e-12);
    expectRaysMatchFormula(camera, 0.7);
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        EXPECT_DOUBLE_EQ(camera.cameraToWorld.m[r][c], written.train.views[v].camera.cameraToWorld.m[r][c]);
  }
}

// A camera with fx != fy and an off-centre principal point (as COLMAP's PINHOLE model has):
// the ray through (px, py) has the camera-space slopes of the pinhole equations, and
// project() inverts generateRay().
TEST(Camera, OffCentrePrincipalPointAndNonSquarePixelsRoundTrip) {
  Camera camera;
  camera.cameraToWorld = Mat4::lookAt(Vec3d(0.3, -2, 1), Vec3d(0, 0, 0.2), Vec3d(0, 0, 1));
  camera.width = 64, camera.height = 40;
  camera.fx = 70.0, camera.fy = 55.0, camera.cx = 29.0, camera.cy = 23.5;
  Mat4 worldToCamera = camera.cameraToWorld.inverse();
  for (double px : {0.5, 13.25, 29.0, 63.5})
    for (double py : {0.5, 23.5, 39.9}) {
      Ray ray = camera.generateRay(px, py);
      Vec3d local = worldToCamera.transformVector(ray.direction);
      EXPECT_NEAR(local.x / -local.z, (px - camera.cx) / camera.fx, 1e-12);
      EXPECT_NEAR(local.y / -local.z, -(py - camera.cy) / camera.fy, 1e-12);
      Vec2d back;
      ASSERT_TRUE(camera.project(worldToCamera, ray.origin + 3.7 * ray.direction, &back));
      EXPECT_NEAR(back.x, px, 1e-9);
      EXPECT_NEAR(back.y, py, 1e-9);
    }
}

// Resizing keeps the horizontal field of view, square pixels and the principal point's
// relative position; halving both sides halves every intrinsic.
TEST(Camera, ResizedScalesTheIntrinsics) {
  Camera camera = Camera::fromFieldOfView(Mat4::identity(), 0.9, 320, 240);
  camera.cx = 150.0, camera.cy = 130.0;
  Camera half = camera.resized(160, 120);
  EXPECT_DOUBLE_EQ(half.fx, 0.5 * camera.fx);
  EXPECT_DOUBLE_EQ(half.fy, 0.5 * camera.fy);
  EXPECT_DOUBLE_EQ(half.cx, 75.0);
  EXPECT_DOUBLE_EQ(half.cy, 65.0);
  Camera wide = Camera::fromFieldOfView(Mat4::identity(), 0.9, 320, 240).resized(640, 360);
  EXPECT_NEAR(wide.fieldOfViewX(), 0.9, 1e-12);
  EXPECT_DOUBLE_EQ(wide.fx, wide.fy);
  EXPECT_DOUBLE_EQ(wide.cy, 180.0);
}

}  // namespace
}  // namespace glint
