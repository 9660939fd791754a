// Progressive rendering: the pass schedule, and that the passes' running mean ends at the
// one-pass render of the same samples.
#include "render/progressive_render.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "common/random_gaussians.h"
#include "raytrace/reference/reference_tracer.h"

namespace glint {
namespace {

TEST(ProgressiveRender, PassesDoubleTheTotalAndEndAtTheSampleCount) {
  EXPECT_EQ(progressivePassSizes(1), (std::vector<int>{1}));
  EXPECT_EQ(progressivePassSizes(2), (std::vector<int>{1, 1}));
  EXPECT_EQ(progressivePassSizes(5), (std::vector<int>{1, 1, 2, 1}));
  EXPECT_EQ(progressivePassSizes(8), (std::vector<int>{1, 1, 2, 4}));
  for (int spp = 1; spp <= 300; ++spp) {
    std::vector<int> sizes = progressivePassSizes(spp);
    EXPECT_EQ(std::accumulate(sizes.begin(), sizes.end(), 0), spp);
    EXPECT_LE(int(sizes.size()), int(std::ceil(std::log2(spp))) + 1);  // logarithmically many files rewrites
  }
}

TEST(ProgressiveRender, RunningMeansEndAtTheOnePassRender) {
  GaussianScene scene = randomScene(200, 11);
  ReferenceTracer tracer;
  tracer.build(scene, TraceSettings{});
  Camera camera;
  camera.cameraToWorld = Mat4::lookAt({0.3, 0.2, 4}, {0, 0, 0}, {0, 1, 0});
  camera.width = 10;
  camera.height = 8;
  camera = Camera::fromFieldOfView(camera.cameraToWorld, 0.9, camera.width, camera.height);
  RenderSettings settings;
  settings.spp = 6;
  settings.seed = 3;
  settings.path.bounces = 2;

  std::vector<int> seen;
  ViewBuffers firstPass;
  ViewBuffers last = renderProgressively(tracer, camera, settings, 2, [&](const ViewBuffers& mean, int samples) {
    if (seen.empty()) firstPass = mean;
    seen.push_back(samples);
  });
  EXPECT_EQ(seen, (std::vector<int>{1, 2, 4, 6}));

  ViewBuffers full = renderGaussianView(tracer, camera, settings, 2);
  float specularTotal = 0;
  for (Buffer b : kAllBuffers)
    for (size_t i = 0; i < full[b].pixels.size(); ++i) {
      float tolerance = 1e-5f * (1.0f + std::abs(full[b].pixels[i]));
      EXPECT_NEAR(last[b].pixels[i], full[b].pixels[i], tolerance) << bufferName(b) << " " << i;
      if (b == Buffer::Specular) specularTotal += full[b].pixels[i];
    }
  EXPECT_GT(specularTotal, 0.0f);  // the bounces were traced

  // The first pass is sample 0 alone, exactly as a render of one sample.
  settings.spp = 1;
  ViewBuffers one = renderGaussianView(tracer, camera, settings, 2);
  for (Buffer b : kAllBuffers) EXPECT_EQ(firstPass[b].pixels, one[b].pixels) << bufferName(b);
}

TEST(ProgressiveRender, AccumulatorWeighsRendersByTheirSamples) {
  ViewAccumulator acc(1, 1);
  ViewBuffers a = ViewBuffers::allocate(1, 1), b = ViewBuffers::allocate(1, 1);
  a[Buffer::Diffuse].setRgb(0, 0, Rgb(1.0f));
  b[Buffer::Diffuse].setRgb(0, 0, Rgb(4.0f));
  a[Buffer::Normal].setRgb(0, 0, Rgb(1, 0, 0));  // mean blended normals
  b[Buffer::Normal].setRgb(0, 0, Rgb(0, 0.5f, 0));
  acc.add(a, 1);
  acc.add(b, 3);
  ViewBuffers m = acc.mean();
  EXPECT_EQ(acc.samples(), 4);
  EXPECT_FLOAT_EQ(m[Buffer::Diffuse].at(0, 0, 0), (1.0f + 3 * 4.0f) / 4);
  Rgb n = m[Buffer::Normal].rgb(0, 0);
  EXPECT_NEAR(length(n), 1.0f, 1e-6f);
  EXPECT_NEAR(n.y / n.x, 1.5f, 1e-5f);  // weighted 1 : 3 before normalising
}

}  // namespace
}  // namespace glint
