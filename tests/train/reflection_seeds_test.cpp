// Reflection seeds: over a mirror floor seen from above, seeds fill only the space the
// mirror shows and no camera sees directly, carry the radiance the specular buffer implies,
// and are not made for rough floors.
#include "train/reflection_seeds.h"

#include <gtest/gtest.h>

#include "bsdf/fresnel.h"
#include "io/temp_folder.h"
#include "plane_dataset.h"
#include "train/training_views.h"

namespace glint {
namespace {

constexpr float kSpecular = 0.1f;

// Training views of the plane z = 0 from a ring of eyes above it, with the given roughness
// and a uniform specular buffer (the reflection of a bright, uniform sky above the cameras),
// written under root and loaded as training targets.
TrainingViews floorViews(const std::filesystem::path& root, float roughness) {
  DatasetSplit train;
  train.name = "train";
  train.width = test::kPlaneWidth;
  train.height = test::kPlaneHeight;
  std::vector<Vec3d> eyes = test::ringOfEyes(8);
  for (size_t i = 0; i < eyes.size(); ++i) {
    train.views.push_back(test::planeView("train", int(i), eyes[i], Vec3d(0.1 * double(i), 0, 0)));
    ViewBuffers b = test::planeBuffers(train.camera(i));
    for (int y = 0; y < train.height; ++y)
      for (int x = 0; x < train.width; ++x) {
        if (b[Buffer::Depth].at(x, y) == 0.0f) continue;
        b[Buffer::Roughness].at(x, y) = roughness;
        b[Buffer::Specular].setRgb(x, y, Rgb(kSpecular));
        b[Buffer::Render].setRgb(x, y, b[Buffer::Diffuse].rgb(x, y) + Rgb(kSpecular));
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
  TrainingViews views = floorViews(folder.path(), 0.02f);
  TraceSettings trace;
  FarFieldSettings s;
  s.reflectionSeeds = 500;
  GaussianScene seeds = reflectionSeeds(s, views, *emptyTracer(trace), trace, 0.1f, 3.5f, 11);
  ASSERT_GT(seeds.size(), 50u);
  EXPECT_LE(seeds.size(), 500u);
  const Rgb fNormal = F_Schlick(Rgb(0.04f), 1.0f), fGrazing = F_Schlick(Rgb(0.04f), 0.05f);
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
    EXPECT_GE(seeds.diffuse[i].x, 0.97f * kSpecular / fGrazing.x);
    EXPECT_LE(seeds.diffuse[i].x, 1.03f * kSpecular / fNormal.x);
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

TEST(ReflectionSeeds, NoneForRoughSurfacesOrWhenSwitchedOff) {
  test::TempFolder folder;
  TrainingViews views = floorViews(folder.path(), 0.5f);
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
