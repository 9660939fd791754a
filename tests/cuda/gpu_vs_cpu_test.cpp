// The GPU tracer against the CPU on the same scenes, rays and samples: hit lists of 10k rays
// equal in order, ray results and rendered views equal within 1e-4 (the largest difference
// printed). Exits 77 (skipped) where no GPU is; scripts/device-check.sh runs it on a lent one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/random_gaussians.h"
#include "math/mat4.h"
#include "raytrace/fast/fast_tracer.h"
#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_renderer.h"
#include "scene/camera.h"
#include "tracers/compute_device.h"

namespace glint {
namespace {

// Both walks of the GPU tracer (cuda/cuda_tracer.h): each ray alone, the warp's together.
const char* const kGpuTracers[] = {"cuda", "cuda-warp"};

struct Difference {
  double largest = 0, sum = 0;
  size_t count = 0;
  void add(double a, double b) {
    const double d = std::abs(a - b);
    largest = std::max(largest, d);
    sum += d;
    ++count;
  }
  double mean() const { return count ? sum / double(count) : 0.0; }
};

// 10k rays through `scene` with the GPU tracer `kind` and the fast CPU tracer.
void expectTheCpusHits(const GaussianScene& scene, const char* kind, bool exactTail) {
  TraceSettings settings;
  settings.exactTail = exactTail;
  settings.minTransmittance = 1e-3f;
  std::vector<TraceRay> rays = randomRays(10000, 52);
  for (size_t i = 0; i < rays.size(); i += 4) rays[i].backfaceSkip = 0.5f;
  FastGaussianTracer cpu;
  cpu.build(scene, settings);
  std::unique_ptr<GaussianTracer> gpu = makeGaussianTracer(kind);
  gpu->build(scene, settings);
  std::vector<RayResult> cpuResults(rays.size()), gpuResults(rays.size());
  std::vector<HitList> cpuHits(rays.size()), gpuHits(rays.size());
  cpu.traceBatch(rays, cpuResults, cpuHits, RayCoherence::Scattered);
  gpu->traceBatch(rays, gpuResults, gpuHits, RayCoherence::Scattered);
  size_t differentLists = 0, hits = 0;
  Difference depth, diffuse, transmittance;
  for (size_t i = 0; i < rays.size(); ++i) {
    const std::vector<HitRecord>&a = gpuHits[i].hits, &b = cpuHits[i].hits;
    bool same = a.size() == b.size() && gpuHits[i].overflowed == cpuHits[i].overflowed;
    for (size_t k = 0; same && k < a.size(); ++k) same = a[k].id == b[k].id && a[k].t == b[k].t && a[k].alpha == b[k].alpha;
    differentLists += !same;
    hits += b.size();
    depth.add(gpuResults[i].depth, cpuResults[i].depth);
    diffuse.add(gpuResults[i].diffuse.x, cpuResults[i].diffuse.x);
    transmittance.add(gpuResults[i].transmittance, cpuResults[i].transmittance);
  }
  std::printf("%s, exact tail %d: %zu rays, %zu hits; lists differing: %zu; largest difference: depth %.3g, diffuse %.3g, "
              "transmittance %.3g\n",
              kind, int(exactTail), rays.size(), hits, differentLists, depth.largest, diffuse.largest,
              transmittance.largest);
  EXPECT_EQ(differentLists, 0u);
  EXPECT_GT(hits, 20 * rays.size());  // dense enough that order matters
  EXPECT_LE(depth.largest, 1e-4);
  EXPECT_LE(diffuse.largest, 1e-4);
  EXPECT_LE(transmittance.largest, 1e-4);
}

TEST(GpuTracer, HitListsOfTenThousandRaysEqualTheCpuInOrder) {
  GaussianScene scene = randomScene(20000, 51);
  for (const char* kind : kGpuTracers)
    for (bool exactTail : {false, true}) expectTheCpusHits(scene, kind, exactTail);
}

TEST(GpuTracer, RefitFollowsMovedGaussians) {
  GaussianScene scene = randomScene(5000, 53);
  TraceSettings settings;
  std::unique_ptr<GaussianTracer> gpu = makeGaussianTracer("cuda-warp");
  gpu->build(scene, settings);
  for (Vec3f& p : scene.position) p += Vec3f(0.05f, 0.0f, 0.0f);
  gpu->refit();
  FastGaussianTracer cpu;
  cpu.build(scene, settings);
  std::vector<TraceRay> rays = randomRays(2000, 54);
  std::vector<RayResult> a(rays.size()), b(rays.size());
  gpu->traceBatch(rays, a, {}, RayCoherence::Scattered);
  cpu.traceBatch(rays, b, {}, RayCoherence::Scattered);
  Difference depth;
  for (size_t i = 0; i < rays.size(); ++i) depth.add(a[i].depth, b[i].depth);
  EXPECT_LE(depth.largest, 1e-4);
}

TEST(GpuTracer, EmptySceneGivesEmptyRays) {
  GaussianScene scene;
  for (const char* kind : kGpuTracers) {
    std::unique_ptr<GaussianTracer> gpu = makeGaussianTracer(kind);
    gpu->build(scene, TraceSettings{});
    RayResult r = gpu->trace({Vec3f(0.0f), Vec3f(0, 0, 1), 0.0f});
    EXPECT_EQ(r.hitCount, 0);
    EXPECT_EQ(r.transmittance, 1.0f);
  }
}

// Every buffer of a view rendered on the GPU and the CPU, per-pixel.
void expectSameViews(const ViewBuffers& gpu, const ViewBuffers& cpu, const std::vector<Image>& gpuBounces,
                     const std::vector<Image>& cpuBounces, const std::string& what) {
  for (int b = 0; b < kBufferCount; ++b) {
    const Image &g = gpu[Buffer(b)], &c = cpu[Buffer(b)];
    ASSERT_EQ(g.pixels.size(), c.pixels.size());
    Difference d;
    for (size_t i = 0; i < g.pixels.size(); ++i) d.add(g.pixels[i], c.pixels[i]);
    std::printf("%s, %s: mean |GPU - CPU| %.3g, largest %.3g\n", what.c_str(), bufferName(Buffer(b)), d.mean(),
                d.largest);
    EXPECT_LE(d.mean(), 1e-4) << what << " " << bufferName(Buffer(b));
  }
  ASSERT_EQ(gpuBounces.size(), cpuBounces.size());
  for (size_t k = 0; k < cpuBounces.size(); ++k) {
    Difference d;
    for (size_t i = 0; i < cpuBounces[k].pixels.size(); ++i) d.add(gpuBounces[k].pixels[i], cpuBounces[k].pixels[i]);
    EXPECT_LE(d.mean(), 1e-4) << what << " bounce " << k + 1;
  }
}

// Views of `scene` rendered by the GPU tracer `kind` and the fast CPU tracer at the same seeds.
void expectTheCpusViews(const GaussianScene& scene, const FastGaussianTracer& cpu, const char* kind) {
  std::unique_ptr<GaussianTracer> gpu = makeGaussianTracer(kind);
  gpu->build(scene, TraceSettings{});
  const Camera camera =
      Camera::fromFieldOfView(Mat4::lookAt(Vec3d(0.3, 0.5, 3.2), Vec3d(0, 0, 0), Vec3d(0, 1, 0)), 0.9, 160, 120);
  for (int bounces : {0, 2, 4}) {
    RenderSettings settings;
    settings.spp = 4;
    settings.seed = 7;
    settings.path.bounces = bounces;
    std::vector<Image> gpuBounces, cpuBounces;
    ViewBuffers g = renderGaussianView(*gpu, camera, settings, 3, &gpuBounces);
    ViewBuffers c = renderGaussianView(cpu, camera, settings, 3, &cpuBounces);
    expectSameViews(g, c, gpuBounces, cpuBounces, std::string(kind) + ", " + std::to_string(bounces) + " bounces");
  }
  // Reflected rays traced in path order (not sorted by origin and octant): the same image.
  RenderSettings unsorted;
  unsorted.spp = 2;
  unsorted.path.bounces = 3;
  unsorted.path.reflectedOrder = ReflectedRayOrder::PathOrder;
  std::vector<Image> none;
  expectSameViews(renderGaussianView(*gpu, camera, unsorted, 2), renderGaussianView(cpu, camera, unsorted, 2), none,
                  none, std::string(kind) + ", reflected rays unsorted");
  // A band of rows, starting at a later sample (as MPI ranks and the viewer render).
  RenderSettings band;
  band.spp = 2;
  band.firstSample = 5;
  band.rowBegin = 37;
  band.rowEnd = 81;
  band.path.bounces = 2;
  expectSameViews(renderGaussianView(*gpu, camera, band, 1), renderGaussianView(cpu, camera, band, 1), none, none,
                  std::string(kind) + ", rows 37-81, samples 5-6");
}

TEST(GpuRenderer, ViewsEqualTheCpuForTheSameSeeds) {
  GaussianScene scene = randomScene(30000, 55);
  FastGaussianTracer cpu;
  cpu.build(scene, TraceSettings{});
  for (const char* kind : kGpuTracers) expectTheCpusViews(scene, cpu, kind);
}

TEST(GpuDevice, AutoPicksTheGpuAndSaysWhich) {
  ResolvedDevice device = resolveDevice(DeviceRequest::Auto);
  EXPECT_TRUE(device.gpu);
  EXPECT_EQ(device.tracer, "cuda");
  EXPECT_NE(device.description.find("GPU"), std::string::npos) << device.description;
  std::printf("%s\n", device.description.c_str());
}

}  // namespace
}  // namespace glint

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  std::string why;
  if (!glint::findGpu(&why)) {
    std::printf("SKIPPED: no GPU: %s\n", why.c_str());
    return 77;
  }
  return RUN_ALL_TESTS();
}
