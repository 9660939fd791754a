// The Gaussian view renderer: pixel-centre rays without jitter, averaging with it.
#include "render/gaussian_renderer.h"

#include <gtest/gtest.h>

#include "math/rng.h"
#include "raytrace/reference/reference_tracer.h"
#include "render/gaussian_path.h"

namespace glint {
namespace {

GaussianScene randomScene(int n, uint64_t seed) {
  GaussianScene scene;
  scene.resize(n);
  Rng rng(seed);
  for (int i = 0; i < n; ++i) {
    scene.position[i] = {rng.uniform() * 2 - 1, rng.uniform() * 2 - 1, rng.uniform() * 2 - 1};
    scene.rotation[i] = {rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f};
    scene.logScale[i] = Vec3f(std::log(0.05f + 0.2f * rng.uniform()));
    scene.opacityLogit[i] = rng.uniform() * 4 - 2;
    scene.diffuse[i] = {rng.uniform(), rng.uniform(), rng.uniform()};
    scene.normal[i] = normalize(Vec3f(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f));
    scene.roughness[i] = rng.uniform();
    scene.f0[i] = Rgb(rng.uniform());
  }
  return scene;
}

Camera testCamera() {
  Camera camera;
  camera.cameraToWorld = Mat4::lookAt({0.2, 0.3, 4}, {0, 0, 0}, {0, 1, 0});
  camera.width = 12;
  camera.height = 9;
  camera = Camera::fromFieldOfView(camera.cameraToWorld, 0.9, camera.width, camera.height);
  return camera;
}

TEST(GaussianRenderer, WithoutJitterEachPixelIsItsCentreRay) {
  GaussianScene scene = randomScene(200, 1);
  ReferenceTracer tracer;
  tracer.build(scene, TraceSettings{});
  Camera camera = testCamera();
  RenderSettings settings;
  settings.jitter = false;
  ViewBuffers b = renderGaussianView(tracer, camera, settings, 0);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      Ray ray = camera.generateRay(x + 0.5, y + 0.5);
      RayResult r = tracer.trace({Vec3f(ray.origin), Vec3f(ray.direction), 0.0f});
      EXPECT_EQ(b[Buffer::Diffuse].rgb(x, y), r.diffuse);
      EXPECT_EQ(b[Buffer::Render].rgb(x, y), r.diffuse);
      EXPECT_EQ(b[Buffer::Depth].at(x, y), r.depth);
      EXPECT_EQ(b[Buffer::Roughness].at(x, y), r.roughness);
      Vec3f n = normalize(r.normal);
      EXPECT_NEAR(b[Buffer::Normal].at(x, y, 0), n.x, 1e-6f);
    }
}

TEST(GaussianRenderer, JitteredSamplesAverageAndAreReproducible) {
  GaussianScene scene = randomScene(200, 2);
  ReferenceTracer tracer;
  tracer.build(scene, TraceSettings{});
  Camera camera = testCamera();
  RenderSettings settings;
  settings.spp = 4;
  settings.seed = 9;
  ViewBuffers a = renderGaussianView(tracer, camera, settings, 3);
  ViewBuffers b = renderGaussianView(tracer, camera, settings, 3);
  EXPECT_EQ(a[Buffer::Diffuse].pixels, b[Buffer::Diffuse].pixels);
  settings.jitter = false;
  ViewBuffers centre = renderGaussianView(tracer, camera, settings, 3);
  EXPECT_NE(a[Buffer::Diffuse].pixels, centre[Buffer::Diffuse].pixels);
  // Averages of values in [0, 1] stay in [0, 1].
  for (float v : a[Buffer::Diffuse].pixels) {
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 1.0f);
  }
}

// Progressive accumulation (the viewer): one-sample renders with firstSample 0..N-1
// average to the N-sample render, buffer by buffer, with bounces.
TEST(GaussianRenderer, OneSampleRendersFromFirstSampleAddUpToTheFullRender) {
  GaussianScene scene = randomScene(200, 5);
  ReferenceTracer tracer;
  tracer.build(scene, TraceSettings{});
  Camera camera = testCamera();
  RenderSettings settings;
  settings.spp = 5;
  settings.seed = 4;
  settings.path.bounces = 2;
  ViewBuffers full = renderGaussianView(tracer, camera, settings, 1);
  ViewBuffers sum = ViewBuffers::allocate(camera.width, camera.height);
  settings.spp = 1;
  for (int s = 0; s < 5; ++s) {
    settings.firstSample = s;
    ViewBuffers one = renderGaussianView(tracer, camera, settings, 1);
    for (Buffer b : {Buffer::Diffuse, Buffer::Specular, Buffer::Depth, Buffer::Roughness})
      for (size_t i = 0; i < sum[b].pixels.size(); ++i) sum[b].pixels[i] += one[b].pixels[i] / 5.0f;
  }
  float specularTotal = 0;
  for (Buffer b : {Buffer::Diffuse, Buffer::Specular, Buffer::Depth, Buffer::Roughness})
    for (size_t i = 0; i < sum[b].pixels.size(); ++i) {
      EXPECT_NEAR(sum[b].pixels[i], full[b].pixels[i], 1e-4f * (1.0f + std::abs(full[b].pixels[i])))
          << bufferName(b) << " " << i;
      if (b == Buffer::Specular) specularTotal += full[b].pixels[i];
    }
  EXPECT_GT(specularTotal, 0.0f);  // the bounces were traced
}

// Bands of rows (how the ranks of an MPI job share one view) stacked in order are the full
// render bit for bit: a pixel's samples and paths do not depend on the band around it. With
// a band boundary inside a wavefront tile, jitter, bounces and per-bounce images.
TEST(GaussianRenderer, BandsOfRowsStackUpToTheFullRender) {
  GaussianScene scene = randomScene(200, 7);
  ReferenceTracer tracer;
  tracer.build(scene, TraceSettings{});
  Camera camera = testCamera();
  RenderSettings settings;
  settings.spp = 3;
  settings.seed = 11;
  settings.path.bounces = 2;
  std::vector<Image> fullBounces;
  ViewBuffers full = renderGaussianView(tracer, camera, settings, 2, &fullBounces);
  const int edges[] = {0, 1, 4, 4, camera.height};  // an empty band too
  ViewBuffers stacked;
  std::vector<float> stackedBounce;
  for (int k = 0; k + 1 < 5; ++k) {
    settings.rowBegin = edges[k];
    settings.rowEnd = edges[k + 1];
    std::vector<Image> bounces;
    ViewBuffers band = renderGaussianView(tracer, camera, settings, 2, &bounces);
    for (Buffer b : kAllBuffers) {
      EXPECT_EQ(band[b].height, edges[k + 1] - edges[k]);
      stacked[b].pixels.insert(stacked[b].pixels.end(), band[b].pixels.begin(), band[b].pixels.end());
    }
    stackedBounce.insert(stackedBounce.end(), bounces[0].pixels.begin(), bounces[0].pixels.end());
  }
  for (Buffer b : kAllBuffers) EXPECT_EQ(stacked[b].pixels, full[b].pixels) << bufferName(b);
  EXPECT_EQ(stackedBounce, fullBounces[0].pixels);
}

// The wavefront renderer against the obviously-correct loop: every pixel's samples traced
// one path at a time with tracePath (same keys, same sample positions), averaged in sample
// order. On the fast tracer with 64 x 48 pixels (so camera rays go in bundles) and 3
// bounces of reflected rays, sorted for tracing; per-bounce images included.
TEST(GaussianRenderer, WavefrontMatchesPerPixelPaths) {
  GaussianScene scene = randomScene(3000, 5);
  for (size_t i = 0; i < scene.size(); ++i) scene.opacityLogit[i] += 2.0f;  // surfaces that reflect
  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer("fast");
  tracer->build(scene, TraceSettings{});
  Camera camera = testCamera();
  camera = camera.resized(64, 48);
  RenderSettings settings;
  settings.spp = 3;
  settings.firstSample = 2;
  settings.seed = 9;
  settings.path.bounces = 3;
  settings.path.invalidNormalLength = 0.3f;
  std::vector<Image> bounceLight;
  ViewBuffers b = renderGaussianView(*tracer, camera, settings, 4, &bounceLight);
  ASSERT_EQ(bounceLight.size(), 3u);
  int reflected = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const uint64_t pixel = uint64_t(y) * uint64_t(camera.width) + uint64_t(x);
      std::vector<std::vector<PathSegment>> paths = tracePixelPaths(*tracer, camera, settings, 4, x, y);
      Rgb diffuse(0.0f), specular(0.0f), bounce1(0.0f);
      float depth = 0;
      for (int s = 0; s < settings.spp; ++s) {
        const std::vector<PathSegment>& p = paths[size_t(s)];
        diffuse += p[0].result.diffuse;
        depth += p[0].result.depth;
        specular += pathSpecular(p);
        if (p.size() > 1) bounce1 += p[1].throughput * p[1].result.diffuse, ++reflected;
        // tracePath with the same keys gives the same path as the recorded one.
        PathResult again = tracePath(*tracer, p[0].ray, settings.path, settings.seed, 4, pixel,
                                     uint64_t(settings.firstSample + s));
        EXPECT_EQ(again.segments, int(p.size()));
      }
      const float inv = 1.0f / float(settings.spp);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(b[Buffer::Diffuse].rgb(x, y)[c], diffuse[c] * inv, 1e-5f) << x << "," << y;
        EXPECT_NEAR(b[Buffer::Specular].rgb(x, y)[c], specular[c] * inv, 1e-5f) << x << "," << y;
        EXPECT_NEAR(bounceLight[0].rgb(x, y)[c], bounce1[c] * inv, 1e-5f) << x << "," << y;
      }
      EXPECT_NEAR(b[Buffer::Depth].at(x, y), depth * inv, 1e-4f);
    }
  EXPECT_GT(reflected, camera.width * camera.height / 4) << "the scene must reflect many paths";
}

}  // namespace
}  // namespace glint
