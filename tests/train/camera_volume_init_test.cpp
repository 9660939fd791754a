// The initialisation of a dataset with final images only: random Gaussians in the cube the
// cameras look at, and a shell in the background colour behind everything.
#include "train/camera_volume_init.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/temp_folder.h"
#include "scene/nerf_synthetic_files.h"

namespace glint {
namespace {

TEST(CameraVolumeInit, FillsTheCubeTheCamerasLookAtAndAddsAWhiteShell) {
  test::TempFolder folder;
  test::writeNerfSyntheticDataset(folder.path(), {{"train", 4}, {"test", 1}}, 64, 48);
  DatasetReading reading;  // white background
  const DenseInit init = initInCameraVolume(Dataset::open(folder.path(), reading), DenseInitSettings{});
  EXPECT_EQ(init.stats.source, InitSource::CameraVolume);
  // 4 views of 64x48 pixels: one Gaussian per 8 pixels, but at least 1,000.
  const size_t volume = 1536;
  EXPECT_EQ(init.stats.shellGaussians, kShellGaussians);
  ASSERT_EQ(init.scene.size(), volume + size_t(kShellGaussians));
  // The cameras stand ~4.12 units from the origin, which they look at: the cube reaches
  // 0.35 x that, and the shell lies at twice the farthest.
  const double distance = std::sqrt(test::kNerfCameraDistance * test::kNerfCameraDistance + 1.0);
  for (size_t i = 0; i < volume; ++i)
    for (int axis = 0; axis < 3; ++axis)
      EXPECT_LE(std::abs(init.scene.position[i][axis]), 0.35 * distance + 1e-4) << i;
  for (size_t i = volume; i < init.scene.size(); ++i) {
    EXPECT_NEAR(length(Vec3d(init.scene.position[i])), 2.0 * distance, 1e-3) << i;
    EXPECT_EQ(init.scene.diffuse[i], Rgb(1.0f));
  }
  // Deterministic.
  const DenseInit again = initInCameraVolume(Dataset::open(folder.path(), reading), DenseInitSettings{});
  EXPECT_EQ(again.scene.position, init.scene.position);

  // Black needs no shell.
  reading.background = AlphaBackground::Black;
  EXPECT_EQ(initInCameraVolume(Dataset::open(folder.path(), reading), DenseInitSettings{}).scene.size(), volume);
}

}  // namespace
}  // namespace glint
