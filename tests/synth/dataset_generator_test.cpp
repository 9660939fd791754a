// The generator writes a dataset that validates clean, with distinct train and test cameras.
#include "synth/dataset_generator.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "scene/dataset.h"
#include "synth/builtin_scenes.h"
#include "synth/camera_paths.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

class TempFolder {
 public:
  TempFolder() {
    path_ = fs::temp_directory_path() / ("glint_synth_test_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path_);
  }
  ~TempFolder() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

TEST(DatasetGenerator, BuiltinSpheresDatasetValidatesClean) {
  TempFolder temp;
  SynthSettings settings;
  settings.trainViews = 3;
  settings.testViews = 2;
  settings.width = 16;
  settings.height = 12;
  settings.spp = 2;
  generateDataset(makeBuiltinScene("spheres"), settings, temp.path());
  std::vector<DatasetProblem> problems = validateDataset(temp.path());
  for (const DatasetProblem& p : problems) ADD_FAILURE() << p.file << ": " << p.message;
  Dataset dataset = Dataset::open(temp.path());
  EXPECT_EQ(dataset.train().views.size(), 3u);
  EXPECT_EQ(dataset.test().views.size(), 2u);
  EXPECT_EQ(dataset.train().width, 16);
  EXPECT_TRUE(dataset.pointCloudPath().has_value());
  // Test cameras lie on another path: none coincides with a training camera.
  for (const DatasetView& test : dataset.test().views)
    for (const DatasetView& train : dataset.train().views)
      EXPECT_GT(length(test.camera.position() - train.camera.position()), 0.05);
  // PNG output: radiance tonemapped, depth still float.
  TempFolder pngFolder;
  settings.format = ImageFormat::Png;
  fs::create_directories(pngFolder.path() / "x");
  generateDataset(makeBuiltinScene("spheres"), settings, pngFolder.path() / "x");
  EXPECT_TRUE(validateDataset(pngFolder.path() / "x").empty());
  EXPECT_TRUE(fs::exists(pngFolder.path() / "x" / "train" / "render" / "render_0000.png"));
  EXPECT_TRUE(fs::exists(pngFolder.path() / "x" / "train" / "depth" / "depth_0000.exr"));
}

// --test-spp renders the test split alone at its own sample count, with the same random
// streams as a dataset rendered at that count throughout; the training split keeps --spp.
TEST(DatasetGenerator, TestSplitUsesItsOwnSampleCount) {
  SynthSettings settings{.trainViews = 1, .testViews = 1, .width = 8, .height = 6, .spp = 16};
  TempFolder temp;
  const fs::path uniform = temp.path() / "uniform", split = temp.path() / "split";
  generateDataset(makeBuiltinScene("spheres"), settings, uniform);
  settings.spp = 1;
  settings.testSpp = 16;
  generateDataset(makeBuiltinScene("spheres"), settings, split);
  auto pixels = [](const fs::path& dataset, const char* file) { return readImage(dataset / file).pixels; };
  EXPECT_EQ(pixels(uniform, "test/render/render_0000.exr"), pixels(split, "test/render/render_0000.exr"));
  EXPECT_EQ(pixels(uniform, "test/specular/specular_0000.exr"),
            pixels(split, "test/specular/specular_0000.exr"));
  EXPECT_NE(pixels(uniform, "train/render/render_0000.exr"),
            pixels(split, "train/render/render_0000.exr"));
}

TEST(DatasetGenerator, PointCloudLiesOnTheDepthSurfaces) {
  ViewBuffers buffers = ViewBuffers::allocate(4, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) {
      buffers[Buffer::Depth].at(x, y) = (x == 0) ? 0.0f : 2.0f;  // first column: no surface
      buffers[Buffer::Diffuse].setRgb(x, y, Rgb(1.0f, 0.5f, 0.0f));
    }
  Camera camera = Camera::fromFieldOfView(Mat4::identity(), 0.8, 4, 3);
  std::vector<DepthView> views;
  views.push_back({buffers[Buffer::Depth], buffers[Buffer::Diffuse], camera});
  PointCloud cloud = pointCloudFromDepth(views, 1000);
  ASSERT_EQ(cloud.positions.size(), 9u);
  for (const Vec3f& p : cloud.positions) EXPECT_NEAR(length(p), 2.0f, 1e-5f);
  EXPECT_NEAR(cloud.colors[0].x, 1.0f, 1e-6f);
  EXPECT_NEAR(cloud.colors[0].y, 0.7354f, 1e-3f);  // sRGB encoding of 0.5
  PointCloud capped = pointCloudFromDepth(views, 3);
  EXPECT_LE(capped.positions.size(), 3u);
}

TEST(CameraPaths, PartialArcsIncludeBothEndsAndLookAtTheTarget) {
  OrbitPath path{{0, 0, 0}, {0, 1, 0}, 2.0f, 1.0f, 1.0f, 0.0f, 0.5f, 1.0f};
  std::vector<Mat4> cameras = orbitCameras(path, 3);
  ASSERT_EQ(cameras.size(), 3u);
  EXPECT_NEAR(cameras[0].column(3).x, 2.0, 1e-6);
  EXPECT_NEAR(cameras[2].column(3).x, -2.0, 1e-5);
  for (const Mat4& m : cameras) {
    Vec3d forward = -m.column(2);
    Vec3d toTarget = normalize(Vec3d(0, 1, 0) - m.column(3));
    EXPECT_NEAR(dot(forward, toTarget), 1.0, 1e-9);
  }
}

TEST(BuiltinScenes, EveryBuiltinSceneIsValidAndUnknownNamesAreRejected) {
  for (const std::string& name : builtinSceneNames()) {
    MeshScene scene = makeBuiltinScene(name);
    EXPECT_NO_THROW(scene.validate("builtin:" + name));
    EXPECT_TRUE(scene.hasCameraRig);
  }
  try {
    makeBuiltinScene("nope");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("builtin:spheres"), std::string::npos);
  }
}

}  // namespace
}  // namespace glint
