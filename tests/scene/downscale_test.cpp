// --downscale: cameras keep their rays through the same scene points, radiance is the box
// mean, and depth and normals keep one surface per pixel.
#include "scene/downscale.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "io/temp_folder.h"
#include "scene/dataset.h"
#include "scene/synthetic_dataset.h"

namespace glint {
namespace {

TEST(DownscaleCamera, PixelBlocksSeeTheSameRays) {
  Camera camera = Camera::fromFieldOfView(Mat4::identity(), 0.8, 801, 603);  // neither divisible by 2
  camera.cx = 400.0, camera.cy = 310.0;
  const Camera small = downscaleCamera(camera, 2);
  EXPECT_EQ(small.width, 400);   // the last column dropped
  EXPECT_EQ(small.height, 301);  // the last row dropped
  // The centre of small pixel (i, j) is the centre of the 2x2 block it covers.
  for (auto [i, j] : {std::pair{0, 0}, {123, 45}, {399, 300}}) {
    const Ray a = small.generateRay(i + 0.5, j + 0.5), b = camera.generateRay(2 * i + 1.0, 2 * j + 1.0);
    EXPECT_NEAR(a.direction.x, b.direction.x, 1e-12);
    EXPECT_NEAR(a.direction.y, b.direction.y, 1e-12);
    EXPECT_NEAR(a.direction.z, b.direction.z, 1e-12);
  }
}

TEST(DownscaleBuffer, RadianceIsTheBlockMeanAndTheRemainderIsDropped) {
  Image image(5, 3, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 3; ++c) image.at(x, y, c) = float(x + 10 * y + 100 * c);
  const Image small = downscaleBuffer(image, Buffer::Render, 2);
  ASSERT_EQ(small.width, 2);
  ASSERT_EQ(small.height, 1);
  EXPECT_FLOAT_EQ(small.at(0, 0, 0), (0 + 1 + 10 + 11) / 4.0f);
  EXPECT_FLOAT_EQ(small.at(1, 0, 2), (2 + 3 + 12 + 13) / 4.0f + 200.0f);
}

TEST(DownscaleBuffer, DepthAveragesSurfacesAndNeedsHalfTheBlock) {
  Image depth(4, 2, 1);
  // Block 0: three surface samples of one no-surface; block 1: one surface sample only.
  depth.at(0, 0) = 2.0f, depth.at(1, 0) = 4.0f, depth.at(0, 1) = 3.0f, depth.at(1, 1) = 0.0f;
  depth.at(2, 0) = 5.0f, depth.at(3, 0) = 1e10f;
  const Image small = downscaleBuffer(depth, Buffer::Depth, 2);
  EXPECT_FLOAT_EQ(small.at(0, 0), 3.0f);  // (2 + 4 + 3) / 3, the background left out
  EXPECT_FLOAT_EQ(small.at(1, 0), 0.0f);  // mostly background: no surface
}

TEST(DownscaleBuffer, NormalsAreRenormalisedAndBackgroundStaysZero) {
  Image normal(4, 2, 3);
  auto set = [&](int x, int y, Vec3f n) {
    for (int c = 0; c < 3; ++c) normal.at(x, y, c) = n[c];
  };
  set(0, 0, {1, 0, 0}), set(1, 0, {0, 1, 0}), set(0, 1, {1, 0, 0}), set(1, 1, {0, 1, 0});
  set(2, 0, {0, 0, 1});  // one of four: the block is background
  const Image small = downscaleBuffer(normal, Buffer::Normal, 2);
  const float s = std::sqrt(0.5f);
  EXPECT_NEAR(small.at(0, 0, 0), s, 1e-6);
  EXPECT_NEAR(small.at(0, 0, 1), s, 1e-6);
  EXPECT_NEAR(small.at(0, 0, 2), 0.0f, 1e-6);
  EXPECT_EQ(small.rgb(1, 0), Rgb(0.0f));
}

// A dataset opened with downscale 2 has half-size cameras and buffers that are the box
// filter of the full ones.
TEST(DownscaleDataset, OpensEveryViewAtHalfResolution) {
  test::TempFolder folder;
  test::writeSyntheticDataset(folder.path());
  const Dataset full = Dataset::open(folder.path());
  DatasetReading reading;
  reading.downscale = 2;
  const Dataset half = Dataset::open(folder.path(), reading);
  EXPECT_EQ(half.downscale(), 2);
  EXPECT_EQ(half.train().width, test::kSyntheticWidth / 2);
  EXPECT_EQ(half.train().height, test::kSyntheticHeight / 2);
  EXPECT_DOUBLE_EQ(half.train().camera(1).fx, full.train().camera(1).fx / 2);
  const Image fullRender = full.loadBuffer(full.train(), 1, Buffer::Render);
  const Image halfRender = half.loadBuffer(half.train(), 1, Buffer::Render);
  ASSERT_EQ(halfRender.width, test::kSyntheticWidth / 2);
  EXPECT_FLOAT_EQ(halfRender.at(1, 1, 0), (fullRender.at(2, 2, 0) + fullRender.at(3, 2, 0) + fullRender.at(2, 3, 0) +
                                           fullRender.at(3, 3, 0)) / 4.0f);
  // Every buffer loads and keeps the dataset's checks (unit normals where depth has a surface).
  EXPECT_NO_THROW(half.loadView(half.test(), 0));

  reading.downscale = 7;  // wider than the 6-pixel height
  EXPECT_THROW(Dataset::open(folder.path(), reading), Error);
}

}  // namespace
}  // namespace glint
