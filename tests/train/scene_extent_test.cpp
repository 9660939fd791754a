// The 3DGS scene extent on cameras at known positions.
#include "train/scene_extent.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace glint {
namespace {

DatasetSplit splitWithCameraCentres(const std::vector<Vec3d>& centres) {
  DatasetSplit split;
  split.name = "train";
  for (size_t i = 0; i < centres.size(); ++i) {
    // Orientation must not matter: only the camera centres enter the extent.
    Mat4 pose = Mat4::translation(centres[i]) * Mat4::rotation(0.8, 0.1 * double(i), 0.3, -0.2);
    DatasetView view;
    view.filePath = "train/render/render_" + std::to_string(i);
    view.camera.cameraToWorld = pose;
    split.views.push_back(view);
  }
  return split;
}

TEST(SceneExtent, IsTheCamerasLargestDistanceFromTheirMeanTimesOnePointOne) {
  // Mean (1, 2, 3); the farthest camera is (1, 2, 3) + (0, 0, 4) at distance 4.
  DatasetSplit split = splitWithCameraCentres(
      {Vec3d(3, 2, 2), Vec3d(-1, 2, 2), Vec3d(1, 4, 2), Vec3d(1, 0, 2), Vec3d(1, 2, 7), Vec3d(1, 2, 3)});
  SceneSphere sphere = sceneSphere(split);
  EXPECT_NEAR(sphere.centre.x, 1.0, 1e-12);
  EXPECT_NEAR(sphere.centre.y, 2.0, 1e-12);
  EXPECT_NEAR(sphere.centre.z, 3.0, 1e-12);
  EXPECT_FLOAT_EQ(sphere.radius, 4.4f);
  EXPECT_FLOAT_EQ(sceneExtent(split), 4.4f);
}

TEST(SceneExtent, SingleCameraHasZeroExtentAndNoCameraIsAnError) {
  EXPECT_EQ(sceneExtent(splitWithCameraCentres({Vec3d(5, 6, 7)})), 0.0f);
  EXPECT_THROW(sceneExtent(splitWithCameraCentres({})), Error);
}

}  // namespace
}  // namespace glint
