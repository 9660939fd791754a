// Dense initialisation: unprojection lands on the known surface, voxel binning keeps only
// voxels hit often enough and averages them, the point-cloud path decodes sRGB, and the
// result does not depend on the thread count.
#include "train/dense_init.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/expect_error.h"
#include "core/parallel.h"
#include "io/point_cloud.h"
#include "io/temp_folder.h"
#include "train/nearest_neighbours.h"
#include "train/plane_dataset.h"
#include "train/room_capture.h"
#include "train/scene_extent.h"

namespace glint {
namespace {

using test::kPlaneHeight;
using test::kPlaneWidth;

// IEC 61966-2-1 decoding of the 8-bit code k, in double.
double srgbDecodeDouble(int k) {
  double e = k / 255.0;
  return e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
}

Camera planeCamera() {
  return Camera::fromFieldOfView(Mat4::lookAt(Vec3d(0.7, -0.4, 3.0), Vec3d(0.2, 0.1, 0.0), Vec3d(0, 1, 0)), 0.9,
                                 kPlaneWidth, kPlaneHeight);
}

TEST(UnprojectDepth, PointsOfAKnownPlaneLandOnIt) {
  Camera camera = planeCamera();
  ViewBuffers buffers = test::planeBuffers(camera);
  Image& depth = buffers[Buffer::Depth];
  depth.at(3, 2) = 0.0f;      // no surface, both encodings
  depth.at(5, 7) = 1.0e10f;
  ColouredPoints points = unprojectDepth(depth, buffers[Buffer::Diffuse], camera, 1);
  ASSERT_EQ(points.positions.size(), size_t(kPlaneWidth * kPlaneHeight - 2));
  for (size_t i = 0; i < points.positions.size(); ++i) {
    EXPECT_NEAR(points.positions[i].z, 0.0f, 1e-5f) << i;
    // The colour is the buffer's value at the pixel, which is the plane's colour there.
    Rgb expected = test::planeColour(Vec3d(points.positions[i]));
    EXPECT_NEAR(points.colours[i].x, expected.x, 1e-4f);
    EXPECT_NEAR(points.colours[i].y, expected.y, 1e-4f);
    EXPECT_NEAR(points.colours[i].z, expected.z, 1e-4f);
  }
}

TEST(UnprojectDepth, StrideTakesOnePixelPerBlock) {
  Camera camera = planeCamera();
  ViewBuffers buffers = test::planeBuffers(camera);
  // 16x12 at stride 3: columns 1, 4, 7, 10, 13 and rows 1, 4, 7, 10.
  ColouredPoints points = unprojectDepth(buffers[Buffer::Depth], buffers[Buffer::Diffuse], camera, 3);
  ASSERT_EQ(points.positions.size(), 20u);
  Ray ray = camera.generateRay(4 + 0.5, 1 + 0.5);  // the second point in scan order
  Vec3f expected(ray.origin + ray.direction * double(buffers[Buffer::Depth].at(4, 1)));
  EXPECT_EQ(points.positions[1], expected);
}

TEST(AutomaticPixelStride, KeepsTheSampleCountWithinBudget) {
  EXPECT_EQ(automaticPixelStride(100 * 160 * 120, 1000000), 2);  // 480k samples
  EXPECT_EQ(automaticPixelStride(200 * 800 * 800, 1000000), 12);  // 889k; stride 11 would give 1.06M
  EXPECT_EQ(automaticPixelStride(1000, 1000000), 1);
  EXPECT_EQ(automaticPixelStride(400, 100), 2);  // exactly on budget
}

TEST(MergeInVoxels, DropsSparseVoxelsAndAveragesTheRest) {
  ColouredPoints points;
  auto add = [&](Vec3f p, Rgb c) {
    points.positions.push_back(p);
    points.colours.push_back(c);
  };
  // Voxel edge 1: three samples in voxel (0,0,0), one in (2,0,0), two in (-1,3,0).
  add({0.1f, 0.2f, 0.3f}, {1.0f, 0.0f, 0.0f});
  add({2.5f, 0.5f, 0.5f}, {9.0f, 9.0f, 9.0f});
  add({-0.5f, 3.25f, 0.5f}, {0.0f, 0.5f, 0.0f});
  add({0.4f, 0.5f, 0.6f}, {0.0f, 1.0f, 0.0f});
  add({0.7f, 0.8f, 0.9f}, {0.0f, 0.0f, 1.0f});
  add({-0.25f, 3.75f, 0.25f}, {0.0f, 1.5f, 1.0f});
  int64_t occupied = 0;
  ColouredPoints merged = mergeInVoxels(points, 1.0f, 2, &occupied);
  EXPECT_EQ(occupied, 3);
  ASSERT_EQ(merged.positions.size(), 2u);
  // Ordered by voxel coordinates: (-1,3,0) before (0,0,0).
  EXPECT_NEAR(merged.positions[0].x, -0.375f, 1e-6f);
  EXPECT_NEAR(merged.positions[0].y, 3.5f, 1e-6f);
  EXPECT_NEAR(merged.positions[0].z, 0.375f, 1e-6f);
  EXPECT_EQ(merged.colours[0], Rgb(0.0f, 1.0f, 0.5f));
  EXPECT_NEAR(merged.positions[1].x, 0.4f, 1e-6f);
  EXPECT_NEAR(merged.positions[1].y, 0.5f, 1e-6f);
  EXPECT_NEAR(merged.positions[1].z, 0.6f, 1e-6f);
  EXPECT_NEAR(merged.colours[1].x, 1.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(merged.colours[1].y, 1.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(merged.colours[1].z, 1.0f / 3.0f, 1e-6f);

  // Threshold 1 keeps the singleton too; threshold 4 keeps nothing.
  EXPECT_EQ(mergeInVoxels(points, 1.0f, 1).positions.size(), 3u);
  EXPECT_TRUE(mergeInVoxels(points, 1.0f, 4).positions.empty());
}

TEST(GaussiansAtPoints, SetTheInitialAttributes) {
  ColouredPoints points;
  for (int i = 0; i < 5; ++i) {
    points.positions.push_back(Vec3f(0.3f * float(i * i), 0.1f * float(i), 0.0f));
    points.colours.push_back(Rgb(0.1f * float(i), 0.2f, 0.3f));
  }
  DenseInitSettings settings;
  GaussianScene scene = gaussiansAtPoints(points, settings, 0.05f);
  ASSERT_EQ(scene.size(), 5u);
  EXPECT_TRUE(scene.consistent());
  std::vector<float> distances = meanNeighbourDistances(points.positions, 3);
  for (size_t i = 0; i < scene.size(); ++i) {
    EXPECT_EQ(scene.position[i], points.positions[i]);
    EXPECT_EQ(scene.diffuse[i], points.colours[i]);
    EXPECT_FLOAT_EQ(scene.logScale[i].x, std::log(distances[i]));
    EXPECT_EQ(scene.logScale[i].x, scene.logScale[i].y);
    EXPECT_EQ(scene.logScale[i].x, scene.logScale[i].z);
    EXPECT_NEAR(scene.opacity(i), 0.1f, 1e-6f);
    EXPECT_EQ(scene.roughness[i], 0.1f);
    EXPECT_EQ(scene.f0[i], Rgb(0.04f));
    EXPECT_EQ(scene.normal[i], Vec3f(0.0f));
    EXPECT_EQ(scene.rotation[i].w, 1.0f);
    EXPECT_EQ(scene.rotation[i].x, 0.0f);
  }

  // Duplicates (distance 0) get a tiny finite scale; a lone point the fallback scale.
  ColouredPoints twins{{Vec3f(1.0f), Vec3f(1.0f)}, {Rgb(0.5f), Rgb(0.5f)}};
  GaussianScene twinScene = gaussiansAtPoints(twins, settings, 0.05f);
  EXPECT_TRUE(std::isfinite(twinScene.logScale[0].x));
  EXPECT_LT(twinScene.scale(0).x, 1e-4f);
  ColouredPoints lone{{Vec3f(1.0f)}, {Rgb(0.5f)}};
  EXPECT_FLOAT_EQ(gaussiansAtPoints(lone, settings, 0.05f).scale(0).x, 0.05f);
}

TEST(SrgbToLinear, MatchesTheStandardCurve) {
  EXPECT_EQ(srgbToLinear(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(srgbToLinear(1.0f), 1.0f);
  EXPECT_FLOAT_EQ(srgbToLinear(0.04045f), 0.04045f / 12.92f);  // the linear segment's end
  EXPECT_NEAR(srgbToLinear(0.5f), 0.2140411f, 1e-6f);
  EXPECT_NEAR(srgbToLinear(128.0f / 255.0f), 0.2158605f, 1e-6f);
}

class DenseInitDataset : public ::testing::Test {
 protected:
  test::TempFolder folder;
};

TEST_F(DenseInitDataset, DepthBuffersGiveGaussiansOnThePlane) {
  test::writePlaneDataset(folder.path(), test::ringOfEyes(6));
  Dataset dataset = Dataset::open(folder.path());
  // 16x12 views a few metres away sample the plane about every 0.2 m, so voxels are
  // made about that size (extent 1.65 / 8) for several samples to share one.
  DenseInitSettings settings;
  settings.pixelStride = 1;
  settings.voxelFraction = 1.0f / 8.0f;
  DenseInit init = initFromDepthBuffers(dataset, settings);
  EXPECT_EQ(init.stats.source, InitSource::DepthBuffers);
  EXPECT_EQ(init.stats.pixelStride, 1);
  EXPECT_EQ(init.stats.pointsUnprojected, 6 * kPlaneWidth * kPlaneHeight);  // every ray hits the plane
  EXPECT_FLOAT_EQ(init.stats.sceneExtent, sceneExtent(dataset.train()));
  EXPECT_FLOAT_EQ(init.stats.voxelSize, init.stats.sceneExtent / 8.0f);
  EXPECT_GT(init.stats.voxelsKept, 0);
  EXPECT_LE(init.stats.voxelsKept, init.stats.voxelsOccupied);
  ASSERT_EQ(int64_t(init.scene.size()), init.stats.voxelsKept);
  EXPECT_TRUE(init.scene.consistent());
  for (size_t i = 0; i < init.scene.size(); ++i) {
    EXPECT_NEAR(init.scene.position[i].z, 0.0f, 1e-5f);
    // A voxel's colour averages samples less than a voxel apart on a smooth colour field.
    Rgb expected = test::planeColour(Vec3d(init.scene.position[i]));
    EXPECT_NEAR(init.scene.diffuse[i].x, expected.x, 0.01f);
    EXPECT_NEAR(init.scene.diffuse[i].y, expected.y, 0.01f);
    EXPECT_NEAR(init.scene.diffuse[i].z, expected.z, 0.01f);
    // Scales are about the spacing of the kept voxels: neither tiny nor scene-sized.
    EXPECT_GT(init.scene.scale(i).x, 0.1f * init.stats.voxelSize);
    EXPECT_LT(init.scene.scale(i).x, 50.0f * init.stats.voxelSize);
  }
}

TEST_F(DenseInitDataset, ResultDoesNotDependOnTheThreadCount) {
  test::writePlaneDataset(folder.path(), test::ringOfEyes(8));
  Dataset dataset = Dataset::open(folder.path());
  DenseInitSettings settings;
  settings.forceDepthBuffers = true;
  settings.voxelFraction = 1.0f / 8.0f;
  auto run = [&](int threads) {
    ThreadLimit limit(threads);
    return denseInitialisation(dataset, settings).scene;
  };
  GaussianScene one = run(1), two = run(2);
  ASSERT_EQ(one.size(), two.size());
  for (size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one.position[i], two.position[i]);
    EXPECT_EQ(one.diffuse[i], two.diffuse[i]);
    EXPECT_EQ(one.logScale[i], two.logScale[i]);
  }
}

TEST_F(DenseInitDataset, PointCloudIsPreferredAndDecodedFromSrgb) {
  test::writePlaneDataset(folder.path(), test::ringOfEyes(3));
  PointCloud cloud;
  for (int i = 0; i < 256; ++i) {
    cloud.positions.push_back(Vec3f(0.01f * float(i % 16), 0.02f * float(i / 16), 0.0f));
    cloud.colors.push_back(Rgb(float(i) / 255.0f, float(255 - i) / 255.0f, float((7 * i) % 256) / 255.0f));
  }
  writePointCloud(folder / "point_cloud_dense.ply", cloud);
  Dataset dataset = Dataset::open(folder.path());

  DenseInit init = denseInitialisation(dataset);
  EXPECT_EQ(init.stats.source, InitSource::PointCloud);
  EXPECT_EQ(init.stats.pointsUnprojected, 256);
  ASSERT_EQ(init.scene.size(), 256u);
  std::vector<float> distances = meanNeighbourDistances(cloud.positions, 3);
  for (size_t i = 0; i < init.scene.size(); ++i) {
    EXPECT_EQ(init.scene.position[i], cloud.positions[i]);
    // The 8-bit code k is stored exactly and decodes to the sRGB curve at k / 255 (here in
    // double, so only float rounding separates the two).
    EXPECT_NEAR(init.scene.diffuse[i].x, srgbDecodeDouble(i), 1e-6);
    EXPECT_NEAR(init.scene.diffuse[i].y, srgbDecodeDouble(255 - int(i)), 1e-6);
    EXPECT_NEAR(init.scene.diffuse[i].z, srgbDecodeDouble((7 * int(i)) % 256), 1e-6);
    EXPECT_FLOAT_EQ(init.scene.scale(i).x, distances[i]);
    EXPECT_NEAR(init.scene.opacity(i), 0.1f, 1e-6f);
  }

  DenseInitSettings forced;
  forced.forceDepthBuffers = true;
  EXPECT_EQ(denseInitialisation(dataset, forced).stats.source, InitSource::DepthBuffers);
}

TEST_F(DenseInitDataset, UnusableInputNamesTheFile) {
  test::writePlaneDataset(folder.path(), test::ringOfEyes(2));
  {
    PointCloud colourless;
    colourless.positions = {Vec3f(0.0f), Vec3f(1.0f)};
    writePointCloud(folder / "point_cloud_dense.ply", colourless);
  }
  Dataset dataset = Dataset::open(folder.path());
  test::expectErrorNaming([&] { denseInitialisation(dataset); }, folder / "point_cloud_dense.ply", "colour");

  DenseInitSettings settings;
  settings.minSamplesPerVoxel = 100000;
  test::expectErrorNaming([&] { initFromDepthBuffers(dataset, settings); }, folder / "train" / "depth",
                          "no voxel");
  settings = {};
  settings.opacity = 1.0f;
  EXPECT_THROW(initFromDepthBuffers(dataset, settings), Error);
}

TEST_F(DenseInitDataset, NoSurfaceAnywhereIsAnError) {
  test::writePlaneDataset(folder.path(), {Vec3d(0, -1, 3)}, 0);
  Dataset dataset = Dataset::open(folder.path());
  test::expectErrorNaming([&] { initFromDepthBuffers(dataset); }, folder / "train" / "depth", "no sampled pixel");
}

// The multi-view consistency check's verdict (init.consistent_depth_only): a view whose depth
// is 30% too far puts points below the plane, and leaving its pixels out removes them, with
// every untrusted sample counted and nothing else changed.
TEST_F(DenseInitDataset, UntrustedDepthIsNotUnprojected) {
  test::PlaneDataset data = test::writePlaneDataset(folder.path(), test::ringOfEyes(6));
  ViewBuffers wrong = data.trainBuffers[0];
  for (float& d : wrong[Buffer::Depth].pixels) d *= 1.3f;
  writeViewBuffers(folder.path(), data.train.views[0], wrong, ImageFormat::Exr);
  Dataset dataset = Dataset::open(folder.path());
  DenseInitSettings settings;
  settings.pixelStride = 1;
  settings.voxelFraction = 1.0f / 8.0f;
  settings.minSamplesPerVoxel = 1;  // else the wrong view's sparser points fall below it on their own
  auto offPlane = [](const GaussianScene& scene) {
    int count = 0;
    for (size_t i = 0; i < scene.size(); ++i) count += std::abs(scene.position[i].z) > 0.05f ? 1 : 0;
    return count;
  };
  const DenseInit all = initFromDepthBuffers(dataset, settings);
  EXPECT_GT(offPlane(all.scene), 0);
  EXPECT_EQ(all.stats.samplesUntrusted, 0);

  // View 0 and the right half of view 1 untrusted.
  const DepthTrust trusted = [](size_t view, size_t pixel) {
    return view != 0 && !(view == 1 && pixel % kPlaneWidth >= kPlaneWidth / 2);
  };
  const DenseInit kept = initFromDepthBuffers(dataset, settings, trusted);
  const int64_t untrusted = kPlaneWidth * kPlaneHeight + (kPlaneWidth / 2) * kPlaneHeight;
  EXPECT_EQ(kept.stats.samplesUntrusted, untrusted);
  EXPECT_EQ(kept.stats.pointsUnprojected, 6 * kPlaneWidth * kPlaneHeight - untrusted);
  ASSERT_GT(kept.scene.size(), 0u);
  EXPECT_EQ(offPlane(kept.scene), 0);
  // denseInitialisation passes the verdict on.
  EXPECT_EQ(denseInitialisation(dataset, settings, trusted).stats.samplesUntrusted, untrusted);

  // At stride 2 only the sampled pixels count: 8x6 of view 0, 4x6 of view 1.
  settings.pixelStride = 2;
  EXPECT_EQ(initFromDepthBuffers(dataset, settings, trusted).stats.samplesUntrusted,
            (kPlaneWidth / 2) * (kPlaneHeight / 2) + (kPlaneWidth / 4) * (kPlaneHeight / 2));

  test::expectErrorNaming([&] { initFromDepthBuffers(dataset, settings, [](size_t, size_t) { return false; }); },
                          folder / "train" / "depth", "consistency check trusts none");
}

// A capture's relative depth aligned to its sparse points is only as accurate as the fit:
// the voxels follow the fits' median residual, so that the views' depths of one surface
// meet in one voxel; a synthetic dataset's metric depth keeps the extent's fraction.
TEST(DenseInitCapture, VoxelsAreNoFinerThanTheDepthFitsAreAccurate) {
  test::TempFolder temp;
  test::writeRoomCapture(temp / "capture", PriorErrors::Monocular);
  const Dataset dataset = Dataset::open(temp / "capture", true, 8);

  DenseInitSettings fine;
  fine.depthResidualVoxels = 0;
  const DenseInit a = initFromDepthBuffers(dataset, fine);
  const DenseInit b = initFromDepthBuffers(dataset, DenseInitSettings{});
  ASSERT_GT(b.stats.depthResidual, 0.0f);
  EXPECT_EQ(a.stats.depthResidual, b.stats.depthResidual);
  EXPECT_FLOAT_EQ(b.stats.voxelSize, std::max(a.stats.voxelSize, 2.0f * b.stats.depthResidual));
  EXPECT_GT(b.stats.voxelSize, a.stats.voxelSize);  // the monocular depth is centimetres off
  // A larger share of the occupied voxels holds two samples or more.
  EXPECT_GT(double(b.stats.voxelsKept) / double(b.stats.voxelsOccupied),
            2.0 * double(a.stats.voxelsKept) / double(a.stats.voxelsOccupied));
}

TEST_F(DenseInitDataset, MetricDepthHasNoFitResidual) {
  test::writePlaneDataset(folder.path(), test::ringOfEyes(6));
  DenseInitSettings settings;
  settings.voxelFraction = 1.0f / 8.0f;  // the plane's sample spacing, as above
  const DenseInit init = initFromDepthBuffers(Dataset::open(folder.path()), settings);
  EXPECT_EQ(init.stats.depthResidual, 0.0f);
}

// A capture without depth starts from its sparse points, and says so (not a point cloud file).
TEST(DenseInitCapture, WithoutDepthStartsFromTheSparsePoints) {
  test::TempFolder temp;
  test::writeRoomCapture(temp / "capture", PriorErrors::None, 32, 24, 500);
  std::filesystem::remove_all(temp / "capture" / "priors" / "depth");
  const Dataset dataset = Dataset::open(temp / "capture", true, 8);
  const DenseInit init = denseInitialisation(dataset);
  EXPECT_EQ(init.stats.source, InitSource::SparsePoints);
  ASSERT_GT(dataset.capture()->points.size(), 400u);  // points3D.txt, one Gaussian each
  EXPECT_EQ(init.scene.size(), dataset.capture()->points.size());
}

}  // namespace
}  // namespace glint
