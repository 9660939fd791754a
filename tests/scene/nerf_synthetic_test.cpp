// The NeRF-synthetic layout: detection, sRGB decoding, alpha composited over white or black
// in linear values, the cameras (OpenGL axes, as Glint's), and transforms_val.json.
#include "scene/nerf_synthetic.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "io/temp_folder.h"
#include "io/transfer.h"
#include "scene/dataset.h"
#include "scene/nerf_synthetic_files.h"
#include "scene/synthetic_dataset.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::TempFolder;

float linearOfCode(float code) { return toLinear(Transfer::Srgb, code / 255.0f); }

TEST(NerfSynthetic, IsDetectedBesideThePapersLayout) {
  TempFolder nerf, paper;
  test::writeNerfSyntheticDataset(nerf.path(), {{"train", 2}, {"test", 1}});
  test::writeSyntheticDataset(paper.path());
  EXPECT_TRUE(isNerfSyntheticFolder(nerf.path()));
  EXPECT_FALSE(isNerfSyntheticFolder(paper.path()));
}

TEST(NerfSynthetic, ImagesAreSrgbDecodedAndCompositedInLinearValues) {
  TempFolder folder;
  test::writeNerfSyntheticDataset(folder.path(), {{"train", 2}, {"test", 1}});
  const Image codes = test::nerfImage(16, 12, 0);  // train/r_0, the first view
  for (AlphaBackground background : {AlphaBackground::White, AlphaBackground::Black}) {
    DatasetReading reading;
    reading.background = background;
    const Dataset dataset = Dataset::open(folder.path(), reading);
    ASSERT_EQ(dataset.train().views.size(), 2u);
    EXPECT_EQ(dataset.train().views[0].filePath, "train/render/render_r_0");
    EXPECT_EQ(dataset.train().width, 16);
    const Image image = dataset.loadBuffer(dataset.train(), 0, Buffer::Render);
    ASSERT_EQ(image.channels, 3);
    const float b = background == AlphaBackground::White ? 1.0f : 0.0f;
    for (int c = 0; c < 3; ++c) {
      // Opaque: the sRGB code decoded. Transparent: the background.
      EXPECT_NEAR(image.at(0, 3, c), linearOfCode(codes.at(0, 3, c) * 255.0f), 1e-6) << c;
      EXPECT_NEAR(image.at(12, 3, c), b, 1e-6) << c;
      // Half covered: alpha mixes linear radiance (light adds), not sRGB codes.
      const float a = 128.0f / 255.0f, colour = linearOfCode(codes.at(1, 3, c) * 255.0f);
      EXPECT_NEAR(image.at(1, 3, c), a * colour + (1.0f - a) * b, 1e-6) << c;
    }
  }
  // The sRGB-space mix differs: code 100 at half cover over white is not the linear mix.
  const float a = 0.5f, linearMix = a * linearOfCode(100) + (1 - a);
  const float srgbMix = toLinear(Transfer::Srgb, a * 100 / 255.0f + (1 - a));
  EXPECT_GT(std::abs(linearMix - srgbMix), 0.01f);
}

// Blender's cameras and Glint's share OpenGL axes: the matrix is used as it is.
TEST(NerfSynthetic, CamerasAreTheFilesMatricesInOpenGlAxes) {
  TempFolder folder;
  test::writeNerfSyntheticDataset(folder.path(), {{"train", 1}, {"test", 1}});
  const Dataset dataset = Dataset::open(folder.path());
  const Camera& camera = dataset.train().camera(0);
  const Mat4 pose = test::nerfCameraPose(0, 8);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_DOUBLE_EQ(camera.cameraToWorld.m[r][c], pose.m[r][c]);
  EXPECT_NEAR(camera.fx, 8.0 / std::tan(test::kNerfCameraAngleX / 2), 1e-9);
  EXPECT_DOUBLE_EQ(camera.cx, 8.0);
  EXPECT_DOUBLE_EQ(camera.cy, 6.0);
  // The origin, which the camera looks at, is at the image centre; a point along the
  // camera's x axis (its right) lands right of the centre, one along its y axis (up) above.
  const Mat4 worldToCamera = camera.cameraToWorld.inverse();
  Vec2d centre, right, up;
  ASSERT_TRUE(camera.project(worldToCamera, Vec3d(0.0), &centre));
  ASSERT_TRUE(camera.project(worldToCamera, pose.column(0) * 0.3, &right));
  ASSERT_TRUE(camera.project(worldToCamera, pose.column(1) * 0.3, &up));
  EXPECT_NEAR(centre.x, 8.0, 1e-9);
  EXPECT_NEAR(centre.y, 6.0, 1e-9);
  EXPECT_GT(right.x, 9.0);
  EXPECT_LT(up.y, 5.0);  // image rows count down from the top
}

TEST(NerfSynthetic, ValServesAsTheTestSplitWithoutATestFile) {
  TempFolder withVal, withBoth;
  test::writeNerfSyntheticDataset(withVal.path(), {{"train", 2}, {"val", 3}});
  EXPECT_EQ(Dataset::open(withVal.path()).split("test").views.size(), 3u);
  test::writeNerfSyntheticDataset(withBoth.path(), {{"train", 2}, {"val", 3}, {"test", 1}});
  EXPECT_EQ(Dataset::open(withBoth.path()).split("test").views.size(), 1u);
}

TEST(NerfSynthetic, OneSplitOpensAndTheOtherIsNamedWhenAskedFor) {
  TempFolder folder;
  test::writeNerfSyntheticDataset(folder.path(), {{"test", 2}});
  const Dataset dataset = Dataset::open(folder.path());
  EXPECT_EQ(dataset.split("test").views.size(), 2u);
  try {
    dataset.split("train");
    FAIL() << "a missing split was returned";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("transforms_train.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("test split only"), std::string::npos) << e.what();
  }
}

TEST(NerfSynthetic, AMissingImageIsNamed) {
  TempFolder folder;
  test::writeNerfSyntheticDataset(folder.path(), {{"train", 2}, {"test", 1}});
  fs::remove(folder / "train" / "r_1.png");
  try {
    Dataset::open(folder.path());
    FAIL() << "opened without train/r_1.png";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("r_1.png: not found"), std::string::npos) << e.what();
  }
  // Cameras alone (as render needs) open without it.
  DatasetReading camerasOnly;
  camerasOnly.requireBuffers = false;
  EXPECT_EQ(Dataset::open(folder.path(), camerasOnly).train().views.size(), 2u);
}

// The paper's layout holding one split renders and evaluates that split.
TEST(OneSplitDataset, ThePapersLayoutOpensWithTheTestSplitOnly) {
  TempFolder folder;
  test::writeSyntheticDataset(folder.path());
  fs::remove(folder / "transforms_train.json");
  const Dataset dataset = Dataset::open(folder.path());
  EXPECT_EQ(dataset.split("test").views.size(), 1u);
  EXPECT_NO_THROW(dataset.loadView(dataset.test(), 0));
  EXPECT_THROW(dataset.split("train"), Error);
  EXPECT_TRUE(validateDataset(folder.path()).empty());
  fs::remove(folder / "transforms_test.json");
  EXPECT_THROW(Dataset::open(folder.path()), Error);
}

}  // namespace
}  // namespace glint
