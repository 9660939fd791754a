// Reflection seeds: over a mirror floor seen from above, seeds fill only the space the
// mirror shows and no camera sees directly, carry the radiance the specular buffer implies,
// stop on a textured ceiling where the views' reflections agree, and are not made for
// rough floors.
#include "train/reflection_seeds.h"

#include <gtest/gtest.h>

#include <cmath>

#include "bsdf/fresnel.h"
#include "io/temp_folder.h"
#include "plane_dataset.h"
#include "train/training_views.h"

namespace glint {
namespace {

constexpr float kSky = 2.0f;  // radiance of the uniform sky above the cameras

// A checkered ceiling at z = kCeiling above the cameras, which look down and never see it.
constexpr double kCeiling = 6.0;
Rgb ceilingRadiance(const Vec3d& p) {
  const int square = int(std::floor(p.x / 0.5)) + int(std::floor(p.y / 0.5));
  return Rgb((square % 2 + 2) % 2 == 0 ? 0.9f : 0.15f);
}

// Training views of the plane z = 0 from a ring of eyes above it, with the given roughness,
// written under root and loaded as training targets. The specular buffer is F x the
// radiance the mirror-reflected ray meets: a bright, uniform sky above the cameras, or with
// `ceiling`, the checkered ceiling; `eyes` and the resolution are the plane dataset's
// unless given.
TrainingViews floorViews(const std::filesystem::path& root, float roughness, bool ceiling = false,
                         std::vector<Vec3d> eyes = test::ringOfEyes(8), int width = test::kPlaneWidth,
                         int height = test::kPlaneHeight) {
  DatasetSplit train;
  train.name = "train";
  train.width = width;
  train.height = height;
  for (size_t i = 0; i < eyes.size(); ++i) {
    train.views.push_back(test::planeView("train", int(i), eyes[i], Vec3d(0.1 * double(i), 0, 0)));
    train.views.back().camera = Camera::fromFieldOfView(train.views.back().camera.cameraToWorld, 0.9, width, height);
    ViewBuffers b = test::planeBuffers(train.camera(i));
    for (int y = 0; y < train.height; ++y)
      for (int x = 0; x < train.width; ++x) {
        if (b[Buffer::Depth].at(x, y) == 0.0f) continue;
        b[Buffer::Roughness].at(x, y) = roughness;
        const Ray eye = train.camera(i).generateRay(x + 0.5, y + 0.5);
        const Vec3d floor = eye.origin + eye.direction * double(b[Buffer::Depth].at(x, y));
        const Vec3d up(eye.direction.x, eye.direction.y, -eye.direction.z);
        const Rgb F = F_Schlick(Rgb(0.04f), float(up.z));
        const Rgb specular = F * (ceiling ? ceilingRadiance(floor + up * (kCeiling / up.z)) : Rgb(kSky));
        b[Buffer::Specular].setRgb(x, y, specular);
        b[Buffer::Render].setRgb(x, y, b[Buffer::Diffuse].rgb(x, y) + specular);
      }
    writeViewBuffers(root, train.views.back(), b, ImageFormat::Exr);
  }
  writeTransforms(root, train);
  DatasetSplit testSplit = train;
  testSplit.name = "test";
  testSplit.views.resize(1);
  testSplit.views[0].filePath = "test/render/render_0000";
  writeViewBuffers(root, testSplit.views[0], test::planeBuffers(testSplit.camera(0)), ImageFormat::Exr);
  writeTransforms(root, testSplit);
  Dataset dataset = Dataset::open(root);
  return TrainingViews::load(dataset, dataset.train());
}

// 24 eyes on a ring above the floor, all looking down at it: enough views and pixels that
// many reflected rays cross each cell of the photo-consistency test.
std::vector<Vec3d> manyEyes() {
  std::vector<Vec3d> eyes;
  for (int i = 0; i < 24; ++i) {
    const double angle = 2.0 * 3.14159265358979 * i / 24;
    eyes.push_back(Vec3d(2.0 * std::cos(angle), 2.0 * std::sin(angle), 3.0 + 0.02 * i));
  }
  return eyes;
}

// The warm-up's scene: nothing but one small Gaussian far away, so no reflection is explained.
std::unique_ptr<GaussianTracer> emptyTracer(const TraceSettings& trace) {
  GaussianScene scene;
  scene.resize(1);
  scene.position[0] = Vec3f(50.0f, 50.0f, 50.0f);
  scene.rotation[0] = Quatf{};
  scene.logScale[0] = Vec3f(-5.0f);
  scene.opacityLogit[0] = 0.0f;
  scene.diffuse[0] = Rgb(0.5f);
  scene.normal[0] = Vec3f(0, 0, 1);
  scene.roughness[0] = 0.5f;
  scene.f0[0] = Rgb(0.04f);
  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer("reference");
  tracer->build(scene, trace);
  return tracer;
}

TEST(ReflectionSeeds, FillOnlyTheUnobservedSpaceTheMirrorShows) {
  test::TempFolder folder;
  TrainingViews views = floorViews(folder.path(), 0.02f, /*ceiling=*/false, manyEyes(), 48, 36);
  TraceSettings trace;
  FarFieldSettings s;
  s.reflectionSeeds = 500;
  GaussianScene seeds = reflectionSeeds(s, views, *emptyTracer(trace), trace, 0.1f, 3.5f, 11);
  ASSERT_GT(seeds.size(), 50u);
  EXPECT_LE(seeds.size(), 500u);
  size_t seenInMirror = 0;
  for (size_t i = 0; i < seeds.size(); ++i) {
    const Vec3d p(seeds.position[i]);
    EXPECT_GT(p.z, 0.0) << "seed " << i << " lies below the mirror";
    const Vec3d mirrored(p.x, p.y, -p.z);
    bool mirroredInView = false;
    for (size_t v = 0; v < views.viewCount(); ++v) {
      const Camera& camera = views.camera(v);
      const Mat4 worldToCamera = camera.cameraToWorld.inverse();
      Vec2d pixel;
      // Directly visible seeds must lie behind the floor the view records (never, as the
      // floor is nearer than anything above it): so no view may see a seed at all.
      if (camera.project(worldToCamera, p, &pixel)) {
        const PixelTarget t = views.target(v, size_t(pixel.y) * size_t(camera.width) + size_t(pixel.x));
        EXPECT_FALSE(t.surface && length(p - camera.position()) < double(t.depth)) << "seed " << i << " view " << v;
      }
      mirroredInView = mirroredInView || camera.project(worldToCamera, mirrored, &pixel);
    }
    seenInMirror += mirroredInView;
    // The colour is the sky's radiance the specular buffer implies: specular / Fresnel
    // (within the training targets' packing: F0 in 8 bits, specular in RGB9E5).
    EXPECT_NEAR(seeds.diffuse[i].x, kSky, 0.03f * kSky);
    EXPECT_EQ(seeds.normal[i], Vec3f(0.0f));  // paths end at them, as at the far field
  }
  // Every seed lies on a ray some camera sees reflected (its mirror image is in a view);
  // the pixel footprint can put a seed a little outside the image of the point it came from.
  EXPECT_GE(double(seenInMirror), 0.95 * double(seeds.size()));

  // The same seed gives the same seeds.
  GaussianScene again = reflectionSeeds(s, views, *emptyTracer(trace), trace, 0.1f, 3.5f, 11);
  ASSERT_EQ(again.size(), seeds.size());
  EXPECT_EQ(again.position[0], seeds.position[0]);
}

// A textured ceiling that only the mirror shows: photo-consistency puts the seeds on it,
// where every view's reflection agrees, with its colour; not in the empty space between,
// which each view sees a different part of the checkerboard through.
TEST(ReflectionSeeds, StopWhereTheViewsReflectionsAgree) {
  test::TempFolder folder;
  TrainingViews views = floorViews(folder.path(), 0.02f, /*ceiling=*/true, manyEyes(), 64, 48);
  TraceSettings trace;
  FarFieldSettings s;
  s.reflectionSeeds = 20000;
  const float sceneRadius = 7.0f, cell = sceneRadius / 48.0f;
  GaussianScene seeds = reflectionSeeds(s, views, *emptyTracer(trace), trace, 0.1f, sceneRadius, 3);
  ASSERT_GT(seeds.size(), 100u);
  size_t onCeiling = 0, rightColour = 0;
  for (size_t i = 0; i < seeds.size(); ++i) {
    const Vec3d p(seeds.position[i]);
    if (std::abs(p.z - kCeiling) > 3.0 * cell) continue;
    ++onCeiling;
    rightColour += std::abs(seeds.diffuse[i].x - ceilingRadiance(p).x) < 0.1f;
  }
  EXPECT_GE(double(onCeiling), 0.8 * double(seeds.size())) << onCeiling << " of " << seeds.size();
  EXPECT_GE(double(rightColour), 0.8 * double(onCeiling)) << rightColour << " of " << onCeiling;
}

TEST(ReflectionSeeds, NoneForRoughSurfacesOrWhenSwitchedOff) {
  test::TempFolder folder;
  TrainingViews views = floorViews(folder.path(), 0.5f, /*ceiling=*/false, manyEyes(), 48, 36);
  TraceSettings trace;
  FarFieldSettings s;
  s.reflectionSeeds = 500;
  EXPECT_EQ(reflectionSeeds(s, views, *emptyTracer(trace), trace, 0.1f, 3.5f, 1).size(), 0u);
  s.reflectionSeedRoughness = 0.6f;  // now the floor counts as a mirror
  EXPECT_GT(reflectionSeeds(s, views, *emptyTracer(trace), trace, 0.1f, 3.5f, 1).size(), 0u);
  s.reflectionSeeds = 0;
  EXPECT_EQ(reflectionSeeds(s, views, *emptyTracer(trace), trace, 0.1f, 3.5f, 1).size(), 0u);
}

}  // namespace
}  // namespace glint
