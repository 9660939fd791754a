// Tests of loadSceneSource: a .ply file, a training run folder with and without
// config.json, and the errors for folders and configs that are not what they should be.
#include "app/scene_source.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/expect_error.h"
#include "scene/gaussian_ply.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

class SceneSourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("glint_scene_source_test_" + std::to_string(getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_ / "run");
    scene_.resize(3);
    for (size_t i = 0; i < scene_.size(); ++i) scene_.position[i] = {float(i), 0.5f, -1.0f};
    writeGaussianPly(root_ / "run" / "scene.ply", scene_);
  }
  void TearDown() override { fs::remove_all(root_); }
  void writeConfig(const std::string& text) { std::ofstream(root_ / "run" / "config.json") << text; }

  fs::path root_;
  GaussianScene scene_;
};

TEST_F(SceneSourceTest, APlyFileHasDefaultSettingsAndNoDataset) {
  SceneSource source = loadSceneSource(root_ / "run" / "scene.ply");
  EXPECT_EQ(source.scene.position, scene_.position);
  EXPECT_TRUE(source.settings.dataset.empty());
  TraceSettings defaults;
  EXPECT_EQ(source.settings.trace.kernelPower, defaults.kernelPower);
  EXPECT_EQ(source.settings.trace.alphaMin, defaults.alphaMin);
  EXPECT_EQ(source.settings.trace.minTransmittance, defaults.minTransmittance);
  // Today's render defaults: the paper's path length 3 and the authors' thresholds.
  PathSettings path = source.settings.path();
  EXPECT_EQ(path.bounces, 2);
  EXPECT_EQ(path.invalidNormalLength, PathSettings{}.invalidNormalLength);
  EXPECT_EQ(path.backfaceSkip, PathSettings{}.backfaceSkip);
}

TEST_F(SceneSourceTest, ARunFolderTakesItsDatasetAndTraceSettingsFromConfig) {
  // Without config.json: the scene alone.
  SceneSource bare = loadSceneSource(root_ / "run");
  EXPECT_EQ(bare.scene.position, scene_.position);
  EXPECT_TRUE(bare.settings.dataset.empty());

  // Every setting of the run is read; missing keys keep their defaults.
  writeConfig(R"({"dataset": "/data/spheres", "iters": 8000, "bounces": 3, "invalid_normal_length": 0.5,
                  "backface_skip": 0.25, "trace": {"kernel_power": 1.5, "alpha_min": 0.01, "exact_tail": true}})");
  SceneSource source = loadSceneSource(root_ / "run");
  EXPECT_EQ(source.settings.dataset, "/data/spheres");
  EXPECT_EQ(source.settings.trace.kernelPower, 1.5f);
  EXPECT_EQ(source.settings.trace.alphaMin, 0.01f);
  EXPECT_TRUE(source.settings.trace.exactTail);
  EXPECT_EQ(source.settings.trace.minTransmittance, TraceSettings{}.minTransmittance);
  PathSettings path = source.settings.path();
  EXPECT_EQ(path.bounces, 3);
  EXPECT_EQ(path.invalidNormalLength, 0.5f);
  EXPECT_EQ(path.backfaceSkip, 0.25f);
}

TEST_F(SceneSourceTest, BadRunsAndConfigsAreRejectedNamingTheFile) {
  fs::create_directories(root_ / "empty");
  test::expectErrorNaming([&] { loadSceneSource(root_ / "empty"); }, root_ / "empty",
                          "is not a training run: no scene.ply");
  test::expectErrorNaming([&] { loadSceneSource(root_ / "missing.ply"); }, root_ / "missing.ply");
  std::ofstream(root_ / "notes.txt") << "hello\n";
  test::expectErrorNaming([&] { loadSceneSource(root_ / "notes.txt"); }, root_ / "notes.txt");

  const fs::path config = root_ / "run" / "config.json";
  for (const char* text : {"{ not json", "[1, 2]", R"({"dataset": 7})", R"({"trace": 3})",
                           R"({"trace": {"kernel_power": "high"}})", R"({"trace": {"alpha_min": 0.9}})",
                           R"({"trace": {"min_transmittance": -0.5}})", R"({"trace": {"kernel_power": 100}})",
                           R"({"invalid_normal_length": -1})", R"({"baseline": "rgbd"})", R"({"itres": 10})"}) {
    writeConfig(text);
    test::expectErrorNaming([&] { loadSceneSource(root_ / "run"); }, config);
  }
}

}  // namespace
}  // namespace glint
