// Camera refinement over training views: a view's camera set again moves its rays and, for
// camera-space normal priors, turns its normal targets; a round of refinement against a model
// brings cameras that were turned and moved back to the cameras the views were seen from.
#include "train/camera_refinement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "common/corner_scene.h"
#include "io/temp_folder.h"
#include "math/nearest_rotation.h"
#include "render/gaussian_renderer.h"
#include "scene/dataset.h"
#include "train/train_config.h"
#include "train/training_eval.h"

namespace glint {
namespace {

using test::cornerCamera;
using test::cornerScene;
using test::disturbed;
using test::kCornerHeight;
using test::kCornerViews;
using test::kCornerWidth;

double degreesBetween(const Camera& a, const Camera& b) {
  return rotationAngleDegrees(a.rotation().transposed() * b.rotation());
}

// The mean distance in pixels between where the corner's visible points project through
// `camera` and through `truth`: what a camera's error does to the images.
double meanReprojectionPixels(const Camera& camera, const Camera& truth, const Image& trueDepth) {
  const Mat4 worldToCamera = camera.cameraToWorld.inverse(), worldToTruth = truth.cameraToWorld.inverse();
  double sum = 0;
  int count = 0;
  for (int y = 0; y < truth.height; ++y)
    for (int x = 0; x < truth.width; ++x) {
      if (!hasSurface(trueDepth.at(x, y))) continue;
      const Ray ray = truth.generateRay(x + 0.5, y + 0.5);
      const Vec3d p = ray.origin + ray.direction * double(trueDepth.at(x, y));
      Vec2d a, b;
      if (!camera.project(worldToCamera, p, &a) || !truth.project(worldToTruth, p, &b)) continue;
      sum += std::hypot(a.x - b.x, a.y - b.y);
      ++count;
    }
  return sum / std::max(count, 1);
}

struct CornerViews {
  test::TempFolder folder;
  GaussianScene scene;  // the tracer reads it: it lives as long as the tracer
  std::unique_ptr<GaussianTracer> tracer;
  std::vector<Camera> truth;
  std::vector<Image> trueDepth;
};

// A dataset whose buffers the model rendered from the true cameras but whose transforms
// hold the disturbed ones: what COLMAP's cameras are to a capture's photographs.
void writeCornerDataset(CornerViews* c, double degrees, double distance) {
  const TrainConfig config;
  c->tracer = makeGaussianTracer("fast");
  c->scene = cornerScene();
  c->tracer->build(c->scene, config.trace);
  DatasetSplit split;
  split.name = "train";
  split.width = kCornerWidth;
  split.height = kCornerHeight;
  RenderSettings centre;
  centre.jitter = false;
  centre.path.bounces = 0;
  for (int v = 0; v < kCornerViews; ++v) {
    c->truth.push_back(cornerCamera(v));
    char file[64];
    std::snprintf(file, sizeof file, "train/render/render_%04d", v);
    split.views.push_back({file, disturbed(c->truth.back(), degrees, distance, v), {}});
    // Radiance averaged over the pixel, G-buffers at its centre: a dataset's convention.
    ViewBuffers b = renderScoredView(*c->tracer, c->truth.back(), scoringSettings(16, PathSettings{}), uint64_t(v));
    writeViewBuffers(c->folder.path(), split.views.back(), b, ImageFormat::Exr);
    c->trueDepth.push_back(b[Buffer::Depth]);
  }
  writeTransforms(c->folder.path(), split);
  DatasetSplit test = split;
  test.name = "test";
  test.views.resize(1);
  test.views[0].filePath = "test/render/render_0000";
  writeViewBuffers(c->folder.path(), test.views[0], renderGaussianView(*c->tracer, c->truth[0], centre, 0),
                   ImageFormat::Exr);
  writeTransforms(c->folder.path(), test);
}

TEST(TrainingViewsCameras, ASetCameraMovesTheRaysAndTurnsCameraSpaceNormalsOnly) {
  CornerViews c;
  writeCornerDataset(&c, 0.0, 0.0);
  const Dataset dataset = Dataset::open(c.folder.path());
  TrainingViews views = TrainingViews::load(dataset, dataset.train());
  const size_t pixel = size_t(kCornerHeight / 2) * kCornerWidth + kCornerWidth / 3;
  const Vec3f loadedNormal = views.target(1, pixel).normal;
  EXPECT_FALSE(views.camerasMoved());

  const Camera turned = disturbed(views.camera(1), 5.0, 0.1, 1);
  views.setCamera(1, turned, /*normalsFromCamera=*/false);
  EXPECT_TRUE(views.camerasMoved());
  const Ray expected = turned.generateRay(kCornerWidth / 3 + 0.5, kCornerHeight / 2 + 0.5);
  const TraceRay ray = views.pixelRay(1, pixel);
  EXPECT_NEAR(length(Vec3d(ray.origin) - expected.origin), 0.0, 1e-5);
  EXPECT_NEAR(length(Vec3d(ray.direction) - expected.direction), 0.0, 1e-6);
  EXPECT_EQ(views.target(1, pixel).normal, loadedNormal);  // a world-space normal stays

  views.setCamera(1, turned, /*normalsFromCamera=*/true);
  const Mat3d turn = turned.rotation() * cornerCamera(1).rotation().transposed();
  const Vec3d turnedNormal = turn * Vec3d(loadedNormal);
  EXPECT_NEAR(length(Vec3d(views.target(1, pixel).normal) - turnedNormal), 0.0, 1e-5);
  EXPECT_NEAR(degreesBetween(turned, cornerCamera(1)), 5.0, 0.01);
  EXPECT_EQ(views.target(0, pixel).normal, TrainingViews::load(dataset, dataset.train()).target(0, pixel).normal);
}

// Cameras 1.2 degrees and 5 cm off (about a COLMAP camera's error at this size, 3 pixels
// here) come back to within a tenth of their image error from a model that is right. A turn
// and a shift across the view look alike in an image, and the model's Gaussians are about a
// pixel wide, so the pose itself comes back less closely than its image.
TEST(CameraRefinement, BringsDisturbedCamerasBackToTheTrueOnes) {
  CornerViews c;
  writeCornerDataset(&c, 1.2, 0.05);
  const Dataset dataset = Dataset::open(c.folder.path());
  TrainingViews views = TrainingViews::load(dataset, dataset.train());
  std::vector<double> before;
  for (size_t v = 0; v < kCornerViews; ++v) {
    ASSERT_GT(degreesBetween(views.camera(v), c.truth[v]), 1.1);
    before.push_back(meanReprojectionPixels(views.camera(v), c.truth[v], c.trueDepth[v]));
    EXPECT_GT(before.back(), 1.5) << "view " << v;
  }

  // The round keeps the frame the disturbed cameras share, so it finds the true cameras less
  // the motion they share with the disturbed ones (small: the disturbances alternate).
  std::vector<Camera> disturbedCameras, expected = c.truth;
  for (size_t v = 0; v < kCornerViews; ++v) disturbedCameras.push_back(views.camera(v));
  removeCommonMotion(disturbedCameras, &expected);

  const CameraRefinementRound round = refineTrainingCameras(*c.tracer, PathSettings{}, &views, false);
  EXPECT_EQ(round.views, kCornerViews);
  EXPECT_EQ(round.moved, kCornerViews);
  EXPECT_GT(round.medianDegrees, 0.7);
  EXPECT_LT(round.costAfter, round.costBefore);
  for (size_t v = 0; v < kCornerViews; ++v) {
    EXPECT_LT(meanReprojectionPixels(views.camera(v), expected[v], c.trueDepth[v]), 0.1 * before[v]) << "view " << v;
    // The pose along the valley where a turn and a shift across the view look alike: views 2
    // and 3 keep 0.7-0.9 degrees of it with a tenth of their image error left.
    EXPECT_LT(degreesBetween(views.camera(v), expected[v]), 1.0) << "view " << v;
  }
  EXPECT_NE(round.summary().find("6 of 6 views moved"), std::string::npos) << round.summary();
}

// A turn, scale and shift that every camera shares is taken out exactly; what each view does on
// its own stays.
TEST(CameraRefinement, RemoveCommonMotionTakesOutWhatAllViewsShare) {
  std::vector<Camera> before, after;
  const Mat3d turn = rotationFromVector(Vec3d(0.01, -0.02, 0.015));
  const Vec3d pivot(0.3, -0.2, 0.5), shift(0.05, 0.02, -0.03);
  const double scale = 1.02;
  for (int v = 0; v < kCornerViews; ++v) {
    before.push_back(cornerCamera(v));
    Camera moved = before.back();
    const Mat3d r = turn * moved.rotation();
    const Vec3d centre = turn * (moved.position() - pivot) * scale + pivot + shift;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) moved.cameraToWorld.m[i][j] = r.m[i][j];
      moved.cameraToWorld.m[i][3] = centre[i];
    }
    after.push_back(moved);
  }
  const auto [degrees, foundScale] = removeCommonMotion(before, &after);
  EXPECT_NEAR(degrees, length(Vec3d(0.01, -0.02, 0.015)) * 180.0 / std::numbers::pi, 1e-6);
  EXPECT_NEAR(foundScale, scale, 1e-9);
  for (int v = 0; v < kCornerViews; ++v) {
    EXPECT_LT(degreesBetween(after[size_t(v)], before[size_t(v)]), 1e-5) << v;  // acos near 1
    EXPECT_LT(length(after[size_t(v)].position() - before[size_t(v)].position()), 1e-9) << v;
  }

  // One view moved on its own among five that stay: most of its motion is its own.
  after = before;
  after[2] = disturbed(before[2], 1.0, 0.05, 2);
  removeCommonMotion(before, &after);
  EXPECT_GT(degreesBetween(after[2], before[2]), 0.6);
}

TEST(CameraRefinement, TheLastRoundIsThreeQuartersOfTheRunUnlessSet) {
  CameraRefinementSettings s;
  s.every = 500;
  EXPECT_EQ(s.lastStep(8000), 6000);
  s.until = 2500;
  EXPECT_EQ(s.lastStep(8000), 2500);
}

}  // namespace
}  // namespace glint
