// Baking reflections into SH: an isolated Gaussian's baked colour, blended as a 3DGS viewer
// does, shows exactly what Glint's tonemapped render shows along rays through it; unseen
// Gaussians keep their diffuse colour; bakes are deterministic.
#include "render/sh_bake.h"

#include <cmath>

#include <gtest/gtest.h>

#include "io/tonemap.h"
#include "math/mat4.h"
#include "math/rng.h"
#include "math/sampling.h"
#include "raytrace/reference/reference_tracer.h"
#include "render/splat_blend.h"

namespace glint {
namespace {

// One Gaussian at the origin, and a second far off that no ray through the first meets.
GaussianScene twoGaussians(float opacity) {
  GaussianScene scene;
  scene.resize(2);
  scene.position = {Vec3f(0.0f), Vec3f(50.0f, 0.0f, 0.0f)};
  scene.rotation = {Quatf{0.9f, 0.1f, -0.3f, 0.2f}, Quatf{}};
  scene.logScale = {Vec3f(std::log(0.2f), std::log(0.05f), std::log(0.1f)), Vec3f(std::log(0.1f))};
  scene.opacityLogit = {logit(opacity), logit(opacity)};
  scene.diffuse = {Rgb(0.3f, 1.5f, 0.05f), Rgb(0.2f, 0.4f, 0.6f)};
  return scene;
}

TEST(ShBake, IsolatedGaussianShowsWhatGlintRendersThroughIt) {
  GaussianScene scene = twoGaussians(0.6f);
  ReferenceTracer tracer;
  tracer.build(scene, TraceSettings{});
  ShBakeSettings settings;  // no cameras: directions over the whole sphere; 0 bounces
  settings.directions = 32;
  SplatColour colour = bakeReflections(scene, tracer, settings);
  ASSERT_TRUE(colour.consistent(2));
  // Along any ray through the mean, L = alpha c with alpha = kMaxAlpha x opacity; the ray's
  // coverage is alpha, so the fit is the constant tonemapFilmic(alpha c) / alpha.
  const float alpha = kMaxAlpha * 0.6f;
  const Rgb expected = tonemapFilmic(scene.diffuse[0] * alpha) / alpha;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(colour.base[0][c], expected[c], 1e-4f);
  for (size_t k = 0; k < colour.restCount(); ++k)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(colour.rest(0)[k][c], 0.0f, 1e-4f);
  // A viewer blending the baked colour sees the tonemapped render, from any side.
  Rng rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    const Vec3f d = sampleUniformSphere(rng.uniform2());
    const TraceRay ray{d * -3.0f, d};
    HitList hits;
    const RayResult r = tracer.trace(ray, &hits);
    const Rgb shown = blendSplatColour(scene, colour, ray.origin, hits);
    const Rgb rendered = tonemapFilmic(r.diffuse);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(shown[c], rendered[c], 2e-3f) << "trial " << trial;
  }
}

TEST(ShBake, GaussianNoRayHitsKeepsItsTonemappedDiffuse) {
  // Opacity so low that alpha stays below alpha_min: every ray passes through it.
  GaussianScene scene = twoGaussians(0.002f);
  ReferenceTracer tracer;
  tracer.build(scene, TraceSettings{});
  ShBakeSettings settings;
  settings.directions = 8;
  SplatColour colour = bakeReflections(scene, tracer, settings);
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(colour.base[0][c], tonemapFilmic(scene.diffuse[0])[c]);
  for (size_t k = 0; k < colour.restCount(); ++k) EXPECT_EQ(colour.rest(0)[k].x, 0.0f);
}

TEST(ShBake, CamerasThatSeeAGaussianSetItsDirections) {
  // A Gaussian in front of a white wall, seen by one camera on +z: every sample comes from
  // the camera's side, where the ray ends on the wall, so the fit is that bright colour in
  // every direction (the ridge keeps the unobserved back side from being extrapolated),
  // where samples over the whole sphere would mix in the dark back view.
  GaussianScene scene = twoGaussians(0.3f);
  scene.position[1] = {0.0f, 0.0f, -1.0f};
  scene.logScale[1] = Vec3f(std::log(2.0f), std::log(2.0f), std::log(0.01f));
  scene.rotation[1] = Quatf{};
  scene.opacityLogit[1] = logit(0.99f);
  scene.diffuse[1] = Rgb(1.0f);
  ReferenceTracer tracer;
  tracer.build(scene, TraceSettings{});
  ShBakeSettings settings;
  settings.directions = 16;
  settings.degree = 1;
  settings.cameras.push_back(Camera::fromFieldOfView(Mat4::lookAt({0, 0, 4}, {0, 0, 0}, {0, 1, 0}), 0.8, 64, 48));
  SplatColour colour = bakeReflections(scene, tracer, settings);
  // What Glint shows along the camera's ray through the Gaussian, normalised by coverage.
  const RayResult r = tracer.trace({Vec3f(0, 0, 1), Vec3f(0, 0, -1)});
  const Rgb target = tonemapFilmic(r.diffuse) / (1.0f - r.transmittance);
  const Rgb front = splatColourAt(colour, 0, Vec3f(0, 0, -1)), back = splatColourAt(colour, 0, Vec3f(0, 0, 1));
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(front[c], target[c], 0.02f);
    EXPECT_NEAR(back[c], target[c], 0.05f);
  }
  settings.cameras.clear();
  SplatColour everywhere = bakeReflections(scene, tracer, settings);
  EXPECT_LT(everywhere.base[0].z, colour.base[0].z - 0.05f);
}

TEST(ShBake, SameSeedSameColours) {
  GaussianScene scene = twoGaussians(0.6f);
  ReferenceTracer tracer;
  tracer.build(scene, TraceSettings{});
  ShBakeSettings settings;
  settings.directions = 8;
  settings.path.bounces = 2;
  settings.seed = 4;
  SplatColour a = bakeReflections(scene, tracer, settings), b = bakeReflections(scene, tracer, settings);
  EXPECT_EQ(a.base, b.base);
  EXPECT_EQ(a.sh, b.sh);
}

}  // namespace
}  // namespace glint
