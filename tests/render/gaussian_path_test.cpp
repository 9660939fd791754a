// Paths through the Gaussians: a near-mirror floor reflects a coloured ceiling exactly as
// an analytic mirror ray traced by hand does; invalid normals end paths; a path is a
// function of its keys alone.
#include "render/gaussian_path.h"

#include <gtest/gtest.h>

#include <cmath>

#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_layers.h"
#include "render/gaussian_renderer.h"

namespace glint {
namespace {

struct MirrorScene {
  GaussianScene scene;
  std::unique_ptr<GaussianTracer> tracer;
  MirrorScene(float floorRoughness, Vec3f floorNormal) {
    // 4 x 4 m layers of flat, nearly opaque Gaussians: the floor and the ceiling.
    test::addLayer(&scene, 0.0f, 0.0f, 0.0f, 41, 41, 0.1f,
                   {Rgb(0.0f), floorNormal, floorRoughness, Rgb(0.5f, 0.6f, 0.7f)});
    test::addLayer(&scene, 0.0f, 0.0f, 3.0f, 41, 41, 0.1f, {Rgb(1.0f, 0.2f, 0.1f), Vec3f(0, 0, -1), 1.0f, Rgb(0.0f)});
    tracer = makeGaussianTracer("fast");
    tracer->build(scene, TraceSettings());
  }
};

TEST(GaussianPath, MirrorFloorReflectsTheCeilingLikeAnAnalyticMirrorRay) {
  MirrorScene m(0.0f, Vec3f(0, 0, 1));
  PathSettings settings;
  settings.bounces = 1;
  for (float dx : {0.0f, 0.2f, -0.35f}) {
    TraceRay primary{Vec3f(0.1f, -0.2f, 1.0f), normalize(Vec3f(dx, 0.1f, -1.0f)), 0.0f};
    PathResult path = tracePath(*m.tracer, primary, settings, 1, 2, 3, 4);
    ASSERT_EQ(path.segments, 2);
    // The reference: the exact mirror direction from the expected termination point.
    const RayResult& first = path.first;
    Vec3f n = normalize(first.normal);
    Vec3f d = primary.direction;
    TraceRay mirror{primary.origin + d * first.depth + n * settings.normalOffset, d - n * (2 * dot(d, n)), 0.0f,
                    settings.backfaceSkip};
    Rgb seen = m.tracer->trace(mirror).diffuse;
    // Schlick Fresnel at this incidence, and the blended F0 (a near-opaque layer blends
    // slightly less than its F0).
    float cosTheta = -dot(d, n);
    Rgb F = first.f0 + (Rgb(1.0f) - first.f0) * std::pow(1 - cosTheta, 5.0f);
    Rgb expected = F * seen;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(path.specular[c], expected[c], 0.01 * expected[c] + 1e-4) << dx;
    EXPECT_GT(path.specular.x, 0.4f);  // ~0.5 x 1.0 of red: the ceiling really is seen
  }
}

TEST(GaussianPath, ShortBlendedNormalEndsThePath) {
  MirrorScene m(0.0f, Vec3f(0, 0, 0.5f));  // blended normal length about 0.5 < 0.7
  PathSettings settings;
  settings.bounces = 2;
  PathResult path = tracePath(*m.tracer, {Vec3f(0, 0, 1), Vec3f(0, 0, -1), 0.0f}, settings, 0, 0, 0, 0);
  EXPECT_EQ(path.segments, 1);
  EXPECT_EQ(path.specular, Rgb(0.0f));
  settings.invalidNormalLength = 0.4f;
  EXPECT_GT(tracePath(*m.tracer, {Vec3f(0, 0, 1), Vec3f(0, 0, -1), 0.0f}, settings, 0, 0, 0, 0).segments, 1);
}

TEST(GaussianPath, RoughPathsDependOnlyOnTheirKeys) {
  MirrorScene m(0.6f, Vec3f(0, 0, 1));
  PathSettings settings;
  settings.bounces = 2;
  TraceRay primary{Vec3f(0, 0, 1), normalize(Vec3f(0.1f, 0, -1)), 0.0f};
  PathResult a = tracePath(*m.tracer, primary, settings, 7, 1, 2, 3);
  PathResult b = tracePath(*m.tracer, primary, settings, 7, 1, 2, 3);
  EXPECT_EQ(a.specular, b.specular);
  // Another sample index gives another direction, hence (almost surely) another value;
  // their mean over many samples is smooth: no sample is wildly off the average.
  Rgb sum(0.0f);
  bool differs = false;
  for (uint64_t s = 0; s < 256; ++s) {
    PathResult p = tracePath(*m.tracer, primary, settings, 7, 1, 2, s);
    differs |= !(p.specular == a.specular);
    sum += p.specular;
  }
  EXPECT_TRUE(differs);
  Rgb mean = sum / 256.0f;
  EXPECT_GT(mean.x, 0.05f);
  EXPECT_LT(mean.x, 0.7f);
}

// The per-bounce light of a path are the terms of its specular sum, in order.
TEST(GaussianPath, BounceLightsAreTheTermsOfTheSpecularSum) {
  GaussianScene scene = test::facingMirrors();
  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer("fast");
  tracer->build(scene, TraceSettings());
  PathSettings settings;
  settings.bounces = 3;
  TraceRay primary{Vec3f(0, 0, 1), normalize(Vec3f(0.05f, 0.02f, -1)), 0.0f};
  int complete = 0;
  for (uint64_t s = 0; s < 16; ++s) {
    PathResult path = tracePath(*tracer, primary, settings, 3, 0, 0, s);
    Rgb sum(0.0f);
    for (int k = 0; k < kSeparateBounces; ++k) {
      sum += path.bounceLight[size_t(k)];
      if (k + 1 >= path.segments) {
        EXPECT_EQ(path.bounceLight[size_t(k)], Rgb(0.0f)) << "segment " << k + 1;
      }
    }
    EXPECT_EQ(sum, path.specular);  // the same additions in the same order
    if (path.segments == 4) {
      ++complete;
      // Bounces 1 and 3 see the blue ceiling, bounce 2 the red floor.
      EXPECT_GT(path.bounceLight[0].z, path.bounceLight[0].x);
      EXPECT_GT(path.bounceLight[1].x, path.bounceLight[1].z);
      EXPECT_GT(path.bounceLight[2].z, path.bounceLight[2].x);
    }
  }
  EXPECT_GT(complete, 8);
}

// Any pixel re-run alone (glint render --debug-pixel) reproduces the full render's value.
TEST(GaussianPath, PixelReRunAloneMatchesTheRender) {
  MirrorScene m(0.3f, Vec3f(0, 0, 1));
  Camera camera = Camera::fromFieldOfView(Mat4::lookAt(Vec3d(0.5, -0.5, 1.5), Vec3d(0, 0, 0), Vec3d(0, 0, 1)), 0.8,
                                          12, 9);
  RenderSettings settings;
  settings.spp = 3;
  settings.seed = 5;
  settings.path.bounces = 2;
  ViewBuffers image = renderGaussianView(*m.tracer, camera, settings, 7);
  for (auto [x, y] : {std::pair{3, 4}, std::pair{11, 0}, std::pair{6, 8}}) {
    std::vector<std::vector<PathSegment>> paths = tracePixelPaths(*m.tracer, camera, settings, 7, x, y);
    ASSERT_EQ(paths.size(), 3u);
    Rgb specular(0.0f), diffuse(0.0f);
    for (const auto& path : paths) {
      diffuse += path[0].result.diffuse;
      Rgb sum(0.0f);
      for (size_t k = 1; k < path.size(); ++k) sum += path[k].throughput * path[k].result.diffuse;
      specular += sum;
    }
    EXPECT_EQ(image[Buffer::Specular].rgb(x, y), specular * (1.0f / 3.0f));
    EXPECT_EQ(image[Buffer::Diffuse].rgb(x, y), diffuse * (1.0f / 3.0f));
  }
  EXPECT_GT(image[Buffer::Specular].rgb(6, 4).x, 0.0f);
}

}  // namespace
}  // namespace glint
