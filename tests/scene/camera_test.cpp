// Pinhole rays against the NeRF/Blender formula, for hand-made and dataset cameras.
#include "scene/camera.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/temp_folder.h"
#include "scene/dataset.h"
#include "scene/synthetic_dataset.h"

namespace glint {
namespace {

// Direction through the centre of pixel (i, j): x = (i + 0.5 - W/2)/f, y = -(j + 0.5 - H/2)/f,
// z = -1 in camera space, mapped by the camera-to-world rotation.
Vec3d expectedDirection(const Camera& camera, int i, int j) {
  double f = 0.5 * camera.width / std::tan(0.5 * camera.fovX);
  Vec3d local((i + 0.5 - 0.5 * camera.width) / f, -(j + 0.5 - 0.5 * camera.height) / f, -1.0);
  const auto& m = camera.cameraToWorld.m;
  Vec3d world(m[0][0] * local.x + m[0][1] * local.y + m[0][2] * local.z,
              m[1][0] * local.x + m[1][1] * local.y + m[1][2] * local.z,
              m[2][0] * local.x + m[2][1] * local.y + m[2][2] * local.z);
  return normalize(world);
}

void expectRaysMatchFormula(const Camera& camera) {
  Vec3d origin(camera.cameraToWorld.m[0][3], camera.cameraToWorld.m[1][3], camera.cameraToWorld.m[2][3]);
  for (int j = 0; j < camera.height; ++j)
    for (int i = 0; i < camera.width; ++i) {
      Ray ray = camera.generateRay(i + 0.5, j + 0.5);
      Vec3d expected = expectedDirection(camera, i, j);
      EXPECT_NEAR(length(ray.direction), 1.0, 1e-12);
      EXPECT_NEAR(length(ray.direction - expected), 0.0, 1e-12) << "pixel " << i << ", " << j;
      EXPECT_NEAR(length(ray.origin - origin), 0.0, 1e-12);
    }
}

TEST(Camera, FocalLengthFromHorizontalFieldOfView) {
  Camera camera;
  camera.width = 800;
  camera.fovX = 2.0 * std::atan(0.5);  // tan(fov/2) = 0.5 -> f = W
  EXPECT_NEAR(camera.focal(), 800.0, 1e-9);
}

TEST(Camera, RaysThroughPixelCentresFollowTheNerfFormula) {
  Camera camera;
  camera.width = 8;
  camera.height = 6;
  camera.fovX = 0.7;
  camera.cameraToWorld = Mat4::lookAt(Vec3d(1, -3, 2), Vec3d(0, 0, 0.5), Vec3d(0, 0, 1));
  expectRaysMatchFormula(camera);
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
    EXPECT_DOUBLE_EQ(camera.fovX, 0.7);
    expectRaysMatchFormula(camera);
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        EXPECT_DOUBLE_EQ(camera.cameraToWorld.m[r][c], written.train.views[v].cameraToWorld.m[r][c]);
  }
}

}  // namespace
}  // namespace glint
