// Opening datasets, buffer paths and file lookup, and write -> load round trips per encoding.
#include "scene/dataset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "core/error.h"
#include "io/temp_folder.h"
#include "io/tonemap.h"
#include "io/transforms_json.h"
#include "scene/synthetic_dataset.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::TempFolder;

TEST(BufferFilePath, ReplacesTheRenderFolderAndStem) {
  EXPECT_EQ(bufferFilePath("train/render/render_0007", Buffer::Depth), "train/depth/depth_0007");
  EXPECT_EQ(bufferFilePath("train/render/render_0007", Buffer::F0), "train/f0/f0_0007");
  EXPECT_EQ(bufferFilePath("train/render/render_0007", Buffer::Render), "train/render/render_0007");
  EXPECT_EQ(bufferFilePath("a/b/render/render_x", Buffer::Roughness), "a/b/roughness/roughness_x");
  EXPECT_EQ(bufferFilePath("render/render_1", Buffer::Normal), "normal/normal_1");
  EXPECT_TRUE(isRenderFilePath("test/render/render_0000"));
  EXPECT_FALSE(isRenderFilePath("train/r_0"));
  EXPECT_FALSE(isRenderFilePath("train/render/r_0"));
  EXPECT_FALSE(isRenderFilePath("render_0000"));
  EXPECT_THROW(bufferFilePath("train/r_0", Buffer::Depth), Error);
}

TEST(Dataset, OpenReadsCamerasSizesAndSortsViews) {
  TempFolder folder;
  test::SyntheticDataset written = test::writeSyntheticDataset(folder.path(), ImageFormat::Exr, 3, 1);
  // Rewrite the train cameras in reverse order: the loader orders views by file_path.
  DatasetSplit reversed = written.train;
  std::reverse(reversed.views.begin(), reversed.views.end());
  writeTransforms(folder.path(), reversed);

  Dataset dataset = Dataset::open(folder.path());
  EXPECT_EQ(dataset.root(), folder.path());
  const DatasetSplit& train = dataset.train();
  EXPECT_EQ(train.name, "train");
  EXPECT_EQ(train.width, test::kSyntheticWidth);
  EXPECT_EQ(train.height, test::kSyntheticHeight);
  EXPECT_NEAR(train.camera(0).fieldOfViewX(), 0.7, 1e-12);
  ASSERT_EQ(train.views.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(train.views[i].filePath, written.train.views[i].filePath);
    EXPECT_EQ(train.views[i].camera.cameraToWorld.m, written.train.views[i].camera.cameraToWorld.m);
    EXPECT_EQ(train.views[i].camera.width, test::kSyntheticWidth);
  }
  EXPECT_EQ(dataset.test().views.size(), 1u);
  EXPECT_EQ(&dataset.split("train"), &dataset.train());
  EXPECT_EQ(&dataset.split("test"), &dataset.test());
  EXPECT_THROW(dataset.split("val"), Error);
  ASSERT_TRUE(dataset.pointCloudPath().has_value());
  EXPECT_EQ(dataset.pointCloudPath()->filename(), "point_cloud_dense.ply");
}

// A folder of photographs (directly, or in images/) without cameras: the error says how to
// get them instead of naming a missing transforms file.
TEST(Dataset, PhotographsWithoutCamerasPointToColmap) {
  for (const char* where : {"", "images"}) {
    test::TempFolder folder;
    std::filesystem::create_directories(folder / where);
    std::ofstream(folder.path() / where / "IMG_0001.JPG") << "not read";
    try {
      Dataset::open(folder.path(), /*requireBuffers=*/false);
      ADD_FAILURE() << "opened a folder of photographs without cameras";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("holds photographs but no cameras"), std::string::npos) << message;
      EXPECT_NE(message.find("glint capture"), std::string::npos) << message;
    }
  }
}

TEST(Dataset, CameraOnlyDatasetsOpenWithoutBuffers) {
  TempFolder folder;
  test::SyntheticDataset written = test::writeSyntheticDataset(folder.path(), ImageFormat::Exr, 2, 1, false);
  fs::remove_all(folder / "train");
  fs::remove_all(folder / "test");
  EXPECT_THROW(Dataset::open(folder.path()), Error);
  Dataset dataset = Dataset::open(folder.path(), false);
  EXPECT_EQ(dataset.train().width, 0);
  EXPECT_EQ(dataset.train().views.size(), 2u);
  EXPECT_FALSE(dataset.pointCloudPath().has_value());
  EXPECT_FALSE(dataset.findBufferFile(dataset.train().views[0], Buffer::Render).has_value());
}

TEST(Dataset, FindBufferFileTriesExrThenTiffThenPng) {
  TempFolder folder;
  test::writeSyntheticDataset(folder.path(), ImageFormat::Png, 2, 1, false);
  Dataset dataset = Dataset::open(folder.path());
  const DatasetView& view = dataset.train().views[1];
  EXPECT_EQ(dataset.findBufferFile(view, Buffer::Diffuse)->filename(), "diffuse_0001.png");
  // Depth is never 8-bit: written as EXR even in a PNG dataset.
  EXPECT_EQ(dataset.findBufferFile(view, Buffer::Depth)->filename(), "depth_0001.exr");

  Image gray(test::kSyntheticWidth, test::kSyntheticHeight, 3, 0.25f);
  writeImage(folder / "train/diffuse/diffuse_0001.tiff", gray);
  EXPECT_EQ(dataset.findBufferFile(view, Buffer::Diffuse)->filename(), "diffuse_0001.tiff");
  writeImage(folder / "train/diffuse/diffuse_0001.exr", gray);
  EXPECT_EQ(dataset.findBufferFile(view, Buffer::Diffuse)->filename(), "diffuse_0001.exr");
  EXPECT_FLOAT_EQ(dataset.loadBuffer(dataset.train(), 1, Buffer::Diffuse).at(2, 3, 1), 0.25f);

  // Writing the view again as PNG removes the files that would shadow the new ones.
  writeViewBuffers(folder.path(), view, test::syntheticBuffers(test::kSyntheticWidth, test::kSyntheticHeight, 1),
                   ImageFormat::Png);
  EXPECT_EQ(dataset.findBufferFile(view, Buffer::Diffuse)->filename(), "diffuse_0001.png");
  EXPECT_FALSE(fs::exists(folder / "train/diffuse/diffuse_0001.tiff"));
}

// Encoding tolerances of docs/data-format.md's table.
struct RoundTripCase {
  ImageFormat format;
  const char* name;
};

void PrintTo(const RoundTripCase& c, std::ostream* out) { *out << c.name; }

class DatasetRoundTrip : public testing::TestWithParam<RoundTripCase> {};

void expectDecodedClose(const Image& loaded, const Image& original, Buffer buffer, ImageFormat format,
                        const Image& depth) {
  ASSERT_EQ(loaded.width, original.width);
  ASSERT_EQ(loaded.height, original.height);
  ASSERT_EQ(loaded.channels, original.channels);
  for (int y = 0; y < loaded.height; ++y)
    for (int x = 0; x < loaded.width; ++x)
      for (int c = 0; c < loaded.channels; ++c) {
        float got = loaded.at(x, y, c), want = original.at(x, y, c);
        SCOPED_TRACE(testing::Message() << bufferName(buffer) << " pixel (" << x << ", " << y << ") channel " << c);
        ASSERT_TRUE(std::isfinite(got));
        if (buffer == Buffer::Depth && !hasSurface(want)) {
          EXPECT_FALSE(hasSurface(got));  // 1e10 may come back as 0 via half-float infinity
          continue;
        }
        if (format == ImageFormat::Exr || (buffer == Buffer::Depth && format == ImageFormat::Png)) {
          EXPECT_EQ(got, want);  // float32
        } else if (format == ImageFormat::Tiff) {
          EXPECT_NEAR(got, want, std::abs(want) * 1e-3f + 1e-6f);  // half: 11-bit mantissa
        } else if (isRadianceBuffer(buffer)) {
          // 8-bit tonemapped: within half a code value in tonemapped space, which is ~1% in
          // linear space near 1 and ~4% near 4 (the curve flattens).
          EXPECT_NEAR(tonemapFilmic(got), tonemapFilmic(want), 0.5f / 255.0f + 1e-5f);
          if (want >= 0.1f && want <= 4.0f) {
            EXPECT_NEAR(got, want, 0.05f * want);
          }
        } else if (buffer == Buffer::Normal) {
          EXPECT_NEAR(got, want, 1.0f / 255.0f + 1e-5f);  // n/2 + 0.5 in 8 bits
          if (hasSurface(depth.at(x, y)) && c == 0) {
            EXPECT_NEAR(length(loaded.rgb(x, y)), 1.0f, 0.01f);
          }
        } else {
          EXPECT_NEAR(got, want, 0.5f / 255.0f + 1e-5f);  // roughness, f0 as-is in 8 bits
        }
      }
}

TEST_P(DatasetRoundTrip, LoadedBuffersMatchWhatWasWritten) {
  TempFolder folder;
  test::SyntheticDataset written = test::writeSyntheticDataset(folder.path(), GetParam().format);
  Dataset dataset = Dataset::open(folder.path());
  for (const DatasetSplit* split : {&dataset.train(), &dataset.test()}) {
    const auto& originals = split == &dataset.train() ? written.trainBuffers : written.testBuffers;
    for (size_t v = 0; v < split->views.size(); ++v) {
      ViewBuffers loaded = dataset.loadView(*split, v);
      for (Buffer b : kAllBuffers) {
        expectDecodedClose(loaded[b], originals[v][b], b, GetParam().format, originals[v][Buffer::Depth]);
        std::string extension = dataset.findBufferFile(split->views[v], b)->extension().string();
        std::string expected = imageFormatExtension(GetParam().format);
        if (b == Buffer::Depth && GetParam().format == ImageFormat::Png) expected = ".exr";
        EXPECT_EQ(extension, expected);
      }
    }
  }
  EXPECT_TRUE(validateDataset(folder.path()).empty());
}

INSTANTIATE_TEST_SUITE_P(Encodings, DatasetRoundTrip,
                         testing::Values(RoundTripCase{ImageFormat::Exr, "exr"},
                                         RoundTripCase{ImageFormat::Tiff, "tiff"},
                                         RoundTripCase{ImageFormat::Png, "png"}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(Dataset, InfiniteDepthMeansNoSurfaceAndLoadsAsZero) {
  TempFolder folder;
  test::writeSyntheticDataset(folder.path());
  fs::path depthPath = folder / "train/depth/depth_0000.exr";
  Image depth = readImage(depthPath);
  depth.at(3, 3) = std::numeric_limits<float>::infinity();
  writeImage(depthPath, depth);

  Dataset dataset = Dataset::open(folder.path());
  Image loaded = dataset.loadBuffer(dataset.train(), 0, Buffer::Depth);
  EXPECT_EQ(loaded.at(3, 3), 0.0f);
  EXPECT_EQ(loaded.at(7, 0), 1.0e10f);  // very large: kept, and also "no surface"
  EXPECT_FALSE(hasSurface(loaded.at(7, 0)));
  // The normal at a no-surface pixel is not checked, so the dataset stays valid.
  EXPECT_TRUE(validateDataset(folder.path()).empty());
}

TEST(Dataset, WriteTransformsStoresTheSplitExactly) {
  TempFolder folder;
  DatasetSplit split;
  split.name = "test";
  const double fovX = 0.6911112070083618;
  const Mat4 pose = Mat4::lookAt(Vec3d(0.1, -4.0, 1.0 / 3.0), Vec3d(0, 0, 0), Vec3d(0, 0, 1));
  split.views.push_back({"test/render/render_0000", Camera::fromFieldOfView(pose, fovX, 800, 800), {}});
  writeTransforms(folder.path(), split);
  TransformsFile read = readTransformsJson(folder / "transforms_test.json");
  EXPECT_NEAR(read.cameraAngleX, fovX, 1e-15);
  ASSERT_EQ(read.frames.size(), 1u);
  EXPECT_EQ(read.frames[0].filePath, "test/render/render_0000");
  EXPECT_EQ(read.frames[0].transformMatrix.m, split.views[0].camera.cameraToWorld.m);
}

}  // namespace
}  // namespace glint
