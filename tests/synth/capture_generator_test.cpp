// A synthesized capture opens as a dataset with LLFF holdout, its cameras are the true
// ones, its depth fits recover metres, and network-like priors differ from exact ones.
#include "synth/capture_generator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include "io/colmap_model.h"
#include "io/temp_folder.h"
#include "scene/dataset.h"
#include "synth/builtin_scenes.h"
#include "synth/camera_paths.h"
#include "synth/ray_caster.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

SynthSettings tinySettings() {
  SynthSettings s;
  s.trainViews = 10;
  s.width = 40;
  s.height = 30;
  s.spp = 2;
  s.testSpp = 4;
  s.bounces = 2;
  return s;
}

TEST(CaptureGenerator, GalleryCaptureOpensWithHoldoutAndTrueCameras) {
  test::TempFolder temp;
  const fs::path root = temp / "capture";
  MeshScene scene = makeBuiltinScene("gallery");
  CaptureSynthSettings capture;
  capture.sparsePoints = 300;
  generateCapture(scene, tinySettings(), capture, root);
  EXPECT_TRUE(fs::exists(root / "images" / "view_0000.jpg"));
  EXPECT_TRUE(fs::exists(root / "priors" / "depth" / "depth_view_0009.png"));
  EXPECT_TRUE(fs::exists(root / "sparse" / "0" / "points3D.txt"));
  EXPECT_TRUE(fs::exists(root / "capture.json"));

  Dataset dataset = Dataset::open(root, true, 8);
  ASSERT_EQ(dataset.test().views.size(), 2u);  // views 0 and 8
  ASSERT_EQ(dataset.train().views.size(), 8u);
  ASSERT_NE(dataset.capture(), nullptr);
  EXPECT_GE(dataset.capture()->points.size(), 250u);
  EXPECT_LE(dataset.capture()->points.size(), 300u);

  const std::vector<Mat4> poses = orbitCameras(scene.cameras.train, 10);
  const Camera& test8 = dataset.test().camera(1);
  EXPECT_NEAR(length(test8.position() - poses[8].column(3)), 0.0, 1e-6);
  EXPECT_NEAR(test8.fx, 40 / (2 * std::tan(scene.cameras.fovX / 2)), 1e-6);
  // Every view's relative depth is fitted to the (exact) points: metres come back.
  ViewBuffers view = dataset.loadView(dataset.train(), 2);
  int surfaces = 0;
  for (float d : view[Buffer::Depth].pixels) surfaces += hasSurface(d);
  EXPECT_EQ(surfaces, 40 * 30);  // a closed room
  auto fits = dataset.capture()->depthFits();
  ASSERT_FALSE(fits.empty());
  for (const auto& [name, fit] : fits) {
    EXPECT_TRUE(fit.ok) << name << ": " << fit.problem;
    EXPECT_LT(fit.medianAbsResidualAfter, 0.05) << name;
  }
}

// The model's tracks name, for each point, the views that see it, as a closest-hit ray
// through the point says: its first hit is the point itself in every view of its track, and
// something nearer in every other view the point projects into. The chrome spheres here
// hide much of the room from views near them.
TEST(CaptureGenerator, TracksHoldTheViewsThatSeeEachPoint) {
  test::TempFolder temp;
  const fs::path root = temp / "capture";
  MeshScene scene = makeBuiltinScene("spheres");
  SynthSettings settings = tinySettings();
  settings.trainViews = 12;
  CaptureSynthSettings capture;
  capture.sparsePoints = 400;
  capture.holdout = 6;
  generateCapture(scene, settings, capture, root);
  const ColmapModel model = readColmapModel(root / "sparse" / "0");
  ASSERT_EQ(model.images.size(), 12u);
  const std::vector<Mat4> poses = orbitCameras(scene.cameras.train, 12);
  RayCaster caster(scene);
  size_t seen = 0, hidden = 0, tracked = 0;
  for (const ColmapPoint& point : model.points) {
    tracked += !point.track.empty();
    std::vector<bool> inTrack(model.images.size(), false);
    for (const ColmapTrackElement& e : point.track) {
      ASSERT_GE(e.imageId, 1u);
      ASSERT_LE(e.imageId, model.images.size());
      const ColmapImage& image = model.images[e.imageId - 1];
      ASSERT_LT(e.point2DIndex, image.points2D.size());
      EXPECT_EQ(image.points2D[e.point2DIndex].point3DId, point.id);
      inTrack[e.imageId - 1] = true;
    }
    for (size_t v = 0; v < model.images.size(); ++v) {
      const Camera camera = Camera::fromFieldOfView(poses[v], scene.cameras.fovX, settings.width, settings.height);
      Vec2d pixel;
      if (!camera.project(camera.cameraToWorld.inverse(), point.xyz, &pixel)) {
        EXPECT_FALSE(inTrack[v]) << "point " << point.id << " is tracked in view " << v << " but not in its image";
        continue;
      }
      const Vec3d toPoint = point.xyz - camera.position();
      const double distance = length(toPoint);
      SurfaceHit hit;
      ASSERT_TRUE(caster.intersect(Vec3f(camera.position()), Vec3f(toPoint / distance), 0.0f, 1e30f, &hit));
      const bool firstHitIsThePoint = std::abs(double(hit.t) - distance) < kSightingTolerance * distance;
      EXPECT_EQ(inTrack[v], firstHitIsThePoint) << "point " << point.id << ", view " << v << ": first hit at "
                                                << hit.t << ", the point at " << distance;
      (inTrack[v] ? seen : hidden)++;
    }
  }
  // Every point was taken from a training view's depth, so some view sees it; and the scene
  // hides a good share of the points that land in a view's image.
  EXPECT_EQ(tracked, model.points.size());
  EXPECT_GT(hidden, seen / 10) << seen << " seen, " << hidden << " hidden";
}

// Three views of the gallery (two training views) with exact priors, and the same views
// with the given errors.
void writeExactAndDegraded(PriorErrors errors, const fs::path& exact, const fs::path& degraded,
                           std::vector<Buffer> only = {}) {
  MeshScene scene = makeBuiltinScene("gallery");
  SynthSettings settings = tinySettings();
  settings.trainViews = 3;
  CaptureSynthSettings capture;
  capture.sparsePoints = 300;
  generateCapture(scene, settings, capture, exact);
  capture.priorErrors = errors;
  capture.degradedPriors = std::move(only);
  generateCapture(scene, settings, capture, degraded);
}

TEST(CaptureGenerator, NetworkLikePriorsDifferFromExactOnesButPhotosDoNot) {
  test::TempFolder temp;
  writeExactAndDegraded(PriorErrors::Network, temp / "exact", temp / "network");
  Dataset exact = Dataset::open(temp / "exact", true, 8), network = Dataset::open(temp / "network", true, 8);
  ASSERT_EQ(exact.train().views.size(), 2u);
  ViewBuffers a = exact.loadView(exact.train(), 0), b = network.loadView(network.train(), 0);
  EXPECT_EQ(a[Buffer::Render].pixels, b[Buffer::Render].pixels);
  double angleSum = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      Vec3d na(a[Buffer::Normal].rgb(x, y)), nb(b[Buffer::Normal].rgb(x, y));
      angleSum += std::acos(std::clamp(dot(normalize(na), normalize(nb)), -1.0, 1.0));
    }
  // 4 degrees of tilt, plus the blur at edges and 8-bit quantisation of both maps.
  double meanAngle = angleSum / (40 * 30) * 180 / std::numbers::pi;
  EXPECT_GT(meanAngle, 2.5);
  EXPECT_LT(meanAngle, 9.0);
  double roughnessShift = 0;
  for (size_t p = 0; p < a[Buffer::Roughness].pixels.size(); ++p)
    roughnessShift += b[Buffer::Roughness].pixels[p] - (0.8 * a[Buffer::Roughness].pixels[p] + 0.1);
  EXPECT_NEAR(roughnessShift / (40 * 30), 0.0, 0.02);
}

// The monocular kind stores metalness instead of F0, as predictors without F0 do: the loader
// reads it back as the grey F0 of the white-base rule, so the gallery's tinted metals lose
// their tint and its dielectrics keep 0.04.
TEST(CaptureGenerator, MonocularPriorsGiveMetalnessInsteadOfF0) {
  test::TempFolder temp;
  writeExactAndDegraded(PriorErrors::Monocular, temp / "exact", temp / "monocular");
  EXPECT_FALSE(fs::exists(temp / "monocular" / "priors" / "f0"));
  EXPECT_TRUE(fs::exists(temp / "monocular" / "priors" / "metalness" / "metalness_view_0001.png"));
  Dataset exact = Dataset::open(temp / "exact", true, 8), monocular = Dataset::open(temp / "monocular", true, 8);
  ViewBuffers a = exact.loadView(exact.train(), 0), b = monocular.loadView(monocular.train(), 0);
  EXPECT_EQ(a[Buffer::Render].pixels, b[Buffer::Render].pixels);
  for (size_t p = 0; p < b[Buffer::F0].pixels.size(); p += 3) {
    const Rgb f(b[Buffer::F0].pixels[p], b[Buffer::F0].pixels[p + 1], b[Buffer::F0].pixels[p + 2]);
    EXPECT_EQ(f.x, f.y);
    EXPECT_EQ(f.y, f.z);
    const float brightest = std::max({a[Buffer::F0].pixels[p], a[Buffer::F0].pixels[p + 1], a[Buffer::F0].pixels[p + 2]});
    EXPECT_NEAR(f.x, brightest, 0.01f) << "pixel " << p / 3;
  }
}

// --degrade-only: the named priors get the errors, the others are written as the exact
// capture writes them (the same files), and F0 left out keeps its file on the monocular kind.
TEST(CaptureGenerator, OnlyTheChosenPriorsAreDegraded) {
  test::TempFolder temp;
  writeExactAndDegraded(PriorErrors::Network, temp / "exact", temp / "roughness", {Buffer::Roughness});
  Dataset exact = Dataset::open(temp / "exact", true, 8), rough = Dataset::open(temp / "roughness", true, 8);
  ViewBuffers a = exact.loadView(exact.train(), 0), b = rough.loadView(rough.train(), 0);
  for (Buffer kept : {Buffer::Render, Buffer::Diffuse, Buffer::Specular, Buffer::Depth, Buffer::Normal, Buffer::F0})
    EXPECT_EQ(a[kept].pixels, b[kept].pixels) << bufferName(kept);
  // The degraded prior is the one the full degradation writes.
  writeExactAndDegraded(PriorErrors::Network, temp / "exact1", temp / "network");
  Dataset network = Dataset::open(temp / "network", true, 8);
  EXPECT_EQ(network.loadView(network.train(), 0)[Buffer::Roughness].pixels, b[Buffer::Roughness].pixels);
  EXPECT_NE(a[Buffer::Roughness].pixels, b[Buffer::Roughness].pixels);

  writeExactAndDegraded(PriorErrors::Monocular, temp / "exact2", temp / "normal", {Buffer::Normal});
  EXPECT_TRUE(fs::exists(temp / "normal" / "priors" / "f0"));
  EXPECT_FALSE(fs::exists(temp / "normal" / "priors" / "metalness"));
  Dataset normal = Dataset::open(temp / "normal", true, 8);
  ViewBuffers c = normal.loadView(normal.train(), 0);
  EXPECT_EQ(a[Buffer::F0].pixels, c[Buffer::F0].pixels);
  EXPECT_EQ(a[Buffer::Roughness].pixels, c[Buffer::Roughness].pixels);
  EXPECT_NE(a[Buffer::Normal].pixels, c[Buffer::Normal].pixels);
}

}  // namespace
}  // namespace glint
