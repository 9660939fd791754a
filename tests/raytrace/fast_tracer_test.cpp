// The fast tracer against the reference tracer (every Gaussian in double precision, full
// sort by (key, id), the shared Compositor) on random overlapping scenes; its AVX2 tests
// against their scalar twins; the buffer-overflow path, refit and degenerate scenes.
#include "raytrace/fast/fast_tracer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/random_gaussians.h"
#include "core/parallel.h"
#include "math/rng.h"
#include "raytrace/compositor.h"
#include "raytrace/fast/bvh8_kernels.h"
#include "raytrace/gaussian_kernel.h"
#include "raytrace/reference/reference_tracer.h"

namespace glint {
namespace {

struct Traced {
  std::vector<RayResult> results;
  std::vector<HitList> hits;
};

// The oracle is the reference tracer: every Gaussian, double precision, sorted by (key, id).
Traced traceOracle(const GaussianScene& scene, const TraceSettings& settings, const std::vector<TraceRay>& rays) {
  ReferenceTracer reference;
  reference.build(scene, settings);
  Traced out{std::vector<RayResult>(rays.size()), std::vector<HitList>(rays.size())};
  parallelFor(int64_t(rays.size()), 16, [&](int64_t i) { out.results[i] = reference.trace(rays[i], &out.hits[i]); });
  return out;
}

Traced traceFast(const FastGaussianTracer& tracer, const std::vector<TraceRay>& rays) {
  Traced out{std::vector<RayResult>(rays.size()), std::vector<HitList>(rays.size())};
  parallelFor(int64_t(rays.size()), 16, [&](int64_t i) { out.results[i] = tracer.trace(rays[i], &out.hits[i]); });
  return out;
}

bool near(float a, float b, float tolerance) { return std::abs(a - b) <= tolerance * std::max(1.0f, std::abs(b)); }
bool near(const Vec3f& a, const Vec3f& b, float tolerance) {
  return near(a.x, b.x, tolerance) && near(a.y, b.y, tolerance) && near(a.z, b.z, tolerance);
}

// Every output within `tolerance` (relative above 1) and the same hits in the same order.
void expectSame(const Traced& got, const Traced& want, float tolerance, const std::string& what) {
  int failures = 0;
  for (size_t i = 0; i < want.results.size() && failures < 5; ++i) {
    const RayResult &a = got.results[i], &b = want.results[i];
    bool same = near(a.diffuse, b.diffuse, tolerance) && near(a.depth, b.depth, tolerance) &&
                near(a.normal, b.normal, tolerance) && near(a.normalLength, b.normalLength, tolerance) &&
                near(a.roughness, b.roughness, tolerance) && near(a.f0, b.f0, tolerance) &&
                near(a.transmittance, b.transmittance, tolerance) && a.hitCount == b.hitCount &&
                a.truncated == b.truncated;
    const std::vector<HitRecord>&ha = got.hits[i].hits, &hb = want.hits[i].hits;
    same = same && ha.size() == hb.size();
    for (size_t k = 0; same && k < ha.size(); ++k) same = ha[k].id == hb[k].id && near(ha[k].t, hb[k].t, tolerance);
    if (!same) {
      ++failures;
      ADD_FAILURE() << what << ", ray " << i << ": diffuse " << a.diffuse.x << " vs " << b.diffuse.x << ", depth "
                    << a.depth << " vs " << b.depth << ", T " << a.transmittance << " vs " << b.transmittance
                    << ", hits " << a.hitCount << " vs " << b.hitCount << " (lists " << ha.size() << " vs "
                    << hb.size() << ")";
    }
  }
}


TEST(FastTracer, MatchesTheOracleOnRandomScenes) {
  GaussianScene scene = randomScene(2000, 11);
  std::vector<TraceRay> rays = randomRays(1200, 12);
  int64_t composited = 0;
  for (const TraceSettings& settings : traceSettingsGrid({1.0f, 3.0f})) {
    FastGaussianTracer tracer;
    tracer.build(scene, settings);
    Traced fast = traceFast(tracer, rays);
    expectSame(fast, traceOracle(scene, settings, rays), 1e-4f, describe(settings));
    for (const RayResult& r : fast.results) composited += r.hitCount;
  }
  // The scenes are dense: rays composite dozens of overlapping Gaussians on average.
  EXPECT_GT(double(composited) / (8.0 * rays.size()), 20.0);
}

TEST(FastTracer, MatchesTheReferenceTracer) {
  GaussianScene scene = randomScene(2000, 15);
  std::vector<TraceRay> rays = randomRays(600, 16);
  TraceSettings settings;
  settings.minTransmittance = 1e-4f;
  FastGaussianTracer fast;
  fast.build(scene, settings);
  ReferenceTracer reference;
  reference.build(scene, settings);
  Traced want{std::vector<RayResult>(rays.size()), std::vector<HitList>(rays.size())};
  for (size_t i = 0; i < rays.size(); ++i) want.results[i] = reference.trace(rays[i], &want.hits[i]);
  expectSame(traceFast(fast, rays), want, 1e-4f, "reference tracer");
}

TEST(FastTracer, OverflowingHitBufferGivesTheSameImage) {
  GaussianScene scene = randomScene(2000, 21);
  std::vector<TraceRay> rays = randomRays(600, 22);
  for (bool exactTail : {false, true}) {
    TraceSettings settings;
    settings.minTransmittance = 1e-4f;
    settings.exactTail = exactTail;
    FastGaussianTracer normal;
    normal.build(scene, settings);
    Traced want = traceFast(normal, rays);
    for (int capacity : {2, 3, 4}) {
      FastGaussianTracer small(capacity);
      small.build(scene, settings);
      Traced got = traceFast(small, rays);
      expectSame(got, want, 1e-6f, "capacity " + std::to_string(capacity) + " " + describe(settings));
      // The small buffer really overflowed and re-traversed.
      FastTraceStats stats;
      for (const TraceRay& ray : rays) small.trace(ray, nullptr, &stats);
      EXPECT_GT(stats.passes, int(2 * rays.size()));
    }
  }
}

TEST(FastTracer, RefitAfterMovingGaussiansMatchesARebuildAndTheOracle) {
  GaussianScene scene = randomScene(2000, 31);
  std::vector<TraceRay> rays = randomRays(600, 32);
  TraceSettings settings;
  settings.kernelPower = 3.0f;
  settings.minTransmittance = 1e-4f;
  FastGaussianTracer refitted;
  refitted.build(scene, settings);
  // Move, rescale, turn and fade the Gaussians; a few left out (no proxy) now get one.
  Rng rng(33);
  for (size_t i = 0; i < scene.size(); ++i) {
    scene.position[i] += Vec3f(uniform(rng, -0.3f, 0.3f), uniform(rng, -0.3f, 0.3f), uniform(rng, -0.3f, 0.3f));
    scene.logScale[i] += Vec3f(uniform(rng, -0.5f, 0.5f));
    scene.rotation[i] = randomRotation(rng);
    scene.opacityLogit[i] += uniform(rng, -1.0f, 1.0f);
  }
  refitted.refit();
  FastGaussianTracer rebuilt;
  rebuilt.build(scene, settings);
  Traced want = traceFast(rebuilt, rays);
  expectSame(traceFast(refitted, rays), want, 1e-6f, "refit vs rebuild");
  expectSame(want, traceOracle(scene, settings, rays), 1e-4f, "refit vs oracle");
}

TEST(FastTracer, RefitWhenALeftOutGaussianGainsAProxyRebuilds) {
  GaussianScene scene = randomScene(300, 41);
  std::vector<TraceRay> rays = randomRays(300, 42);
  TraceSettings settings;
  for (size_t i = 0; i < scene.size(); i += 3) scene.opacityLogit[i] = logit(0.001f);  // below alphaMin
  FastGaussianTracer tracer;
  tracer.build(scene, settings);
  EXPECT_EQ(tracer.bvh().stats().gaussians, 200u);
  for (size_t i = 0; i < scene.size(); i += 3) scene.opacityLogit[i] = logit(0.9f);
  tracer.refit();
  EXPECT_EQ(tracer.bvh().stats().gaussians, 300u);
  expectSame(traceFast(tracer, rays), traceOracle(scene, settings, rays), 1e-4f, "after refit");
}

TEST(FastTracer, CoincidentGaussiansTieByIdAndKeepTheTreeShallow) {
  // 3000 identical Gaussians at one point (every key ties; the builder's median split)
  // plus a few distinct ones.
  GaussianScene scene = randomScene(3100, 51);
  for (size_t i = 0; i < 3000; ++i) {
    scene.position[i] = {0.1f, 0.2f, 0.3f};
    scene.rotation[i] = Quatf{};
    scene.logScale[i] = Vec3f(-2.0f);
    scene.opacityLogit[i] = logit(0.05f);
  }
  TraceSettings settings;
  settings.minTransmittance = 1e-4f;
  FastGaussianTracer tracer(8);
  tracer.build(scene, settings);
  EXPECT_LE(tracer.bvh().stats().depth, 40);
  std::vector<TraceRay> rays = randomRays(150, 52);
  for (size_t i = 0; i < rays.size(); i += 2) rays[i].direction = normalize(Vec3f(0.1f, 0.2f, 0.3f) - rays[i].origin);
  expectSame(traceFast(tracer, rays), traceOracle(scene, settings, rays), 1e-4f, "coincident");
}

TEST(FastTracer, EmptySingleAndTransparentScenes) {
  TraceSettings settings;
  TraceRay ray{{0, 0, -3}, {0, 0, 1}};
  GaussianScene empty;
  FastGaussianTracer tracer;
  tracer.build(empty, settings);
  RayResult r = tracer.trace(ray);
  EXPECT_EQ(r.hitCount, 0);
  EXPECT_EQ(r.transmittance, 1.0f);

  GaussianScene single = randomScene(1, 61);
  single.position[0] = {0, 0, 0};
  single.opacityLogit[0] = logit(0.7f);
  tracer.build(single, settings);
  std::vector<TraceRay> rays = randomRays(90, 62);
  rays.push_back(ray);
  Traced want = traceOracle(single, settings, rays);
  expectSame(traceFast(tracer, rays), want, 1e-4f, "single");
  EXPECT_EQ(want.results.back().hitCount, 1);

  GaussianScene transparent = randomScene(500, 63);
  for (float& o : transparent.opacityLogit) o = logit(0.004f);  // 0.9999 * 0.004 < alphaMin
  tracer.build(transparent, settings);
  EXPECT_TRUE(tracer.bvh().empty());
  r = tracer.trace(ray);
  EXPECT_EQ(r.hitCount, 0);
  EXPECT_EQ(r.transmittance, 1.0f);
}

TEST(FastTracer, LaneDataMatchesTheKernelFrameAndBoxesHoldTheProxies) {
  GaussianScene scene = randomScene(500, 81);
  Rng rng(82);
  for (float power : {1.0f, 2.0f, 3.0f, 2.5f}) {
    TraceSettings settings;
    settings.kernelPower = power;
    for (size_t i = 0; i < scene.size(); ++i) {
      GaussianLane lane;
      Box3 box;
      ASSERT_TRUE(computeGaussianLane(scene, i, settings, &lane, &box));
      GaussianFrame<double> frame = makeGaussianFrame<double>(scene, i, settings);
      // Float rounding, relative to the row's length (the inverse scale).
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(lane.worldToLocal[3 * r + c], frame.worldToLocal.m[r][c], 1e-6 * length(frame.worldToLocal.m[r]));
      EXPECT_NEAR(lane.opacity, frame.opacity, 1e-6);
      EXPECT_NEAR(lane.radius2, frame.proxyRadius * frame.proxyRadius, 1e-5 * frame.proxyRadius * frame.proxyRadius);
      // Points on the proxy ellipsoid (local radius R) lie inside the box.
      Mat3d localToWorld = quatToRotation(Quatd{scene.rotation[i].w, scene.rotation[i].x, scene.rotation[i].y,
                                                scene.rotation[i].z});
      Vec3d scale(std::exp(double(scene.logScale[i].x)), std::exp(double(scene.logScale[i].y)),
                  std::exp(double(scene.logScale[i].z)));
      for (int k = 0; k < 200; ++k) {
        Vec3d u = Vec3d(randomDirection(rng)) * frame.proxyRadius;
        Vec3d p = frame.mean + localToWorld * (u * scale);
        for (int a = 0; a < 3; ++a) {
          ASSERT_LE(box.lower[a], p[a]);
          ASSERT_GE(box.upper[a], p[a]);
        }
      }
    }
  }
  // No proxy: opacity so low that alpha never reaches alphaMin, or broken parameters.
  TraceSettings settings;
  GaussianLane lane;
  Box3 box;
  scene.opacityLogit[0] = logit(0.004f);
  EXPECT_FALSE(computeGaussianLane(scene, 0, settings, &lane, &box));
  scene.position[1].y = std::nanf("");
  EXPECT_FALSE(computeGaussianLane(scene, 1, settings, &lane, &box));
  scene.logScale[2].z = 200.0f;
  EXPECT_FALSE(computeGaussianLane(scene, 2, settings, &lane, &box));
}

// The fast tracer over a random scene of 4000 Gaussians, for the tests of its kernels.
struct KernelTestScene {
  GaussianScene scene;  // before the tracer, which keeps a reference to it
  FastGaussianTracer tracer;
  explicit KernelTestScene(uint64_t seed) : scene(randomScene(4000, seed)) { tracer.build(scene, TraceSettings{}); }
};

// Lane i of a and lane j of b hold the same proxy test results, bit for bit.
void expectSameLane(const Bvh8BlockCandidates& a, int i, const Bvh8BlockCandidates& b, int j) {
  ASSERT_EQ(a.tPeak[i], b.tPeak[j]);
  ASSERT_EQ(a.half[i], b.half[j]);
  ASSERT_EQ(a.r2[i], b.r2[j]);
  for (int k = 0; k < 3; ++k) ASSERT_EQ(a.localPoint[k][i], b.localPoint[k][j]);
}

#ifdef __AVX2__
TEST(FastTracer, Avx2TestsAreBitIdenticalToTheScalarOnes) {
  KernelTestScene built(71);
  const Bvh8& bvh = built.tracer.bvh();
  std::vector<TraceRay> rays = randomRays(200, 72);
  rays.push_back({{0.1f, 0.2f, -3}, {0, 0, 1}});  // zero direction components
  rays.push_back({{0.3f, -4, 0.2f}, {0, 1, 0}});
  int leafHits = 0;
  for (const TraceRay& traceRay : rays) {
    Bvh8Ray ray(traceRay);
    for (size_t n = 0; n < bvh.stats().nodes; n += 7) {
      alignas(32) float a[kBvhWidth], b[kBvhWidth];
      uint32_t ma = intersectNodeAvx2(bvh.nodes()[n], ray, a), mb = intersectNodeScalar(bvh.nodes()[n], ray, b);
      ASSERT_EQ(ma, mb);
      for (int c = 0; c < kBvhWidth; ++c) {
        if (ma & (1u << c)) {
          ASSERT_EQ(a[c], b[c]);
        }
      }
    }
    for (size_t l = 0; l < bvh.stats().blocks; l += 3) {
      Bvh8BlockCandidates a, b;
      uint32_t ma = intersectBlockAvx2(bvh.blocks()[l], ray, &a), mb = intersectBlockScalar(bvh.blocks()[l], ray, &b);
      ASSERT_EQ(ma, mb);
      for (int i = 0; i < kBvhWidth; ++i) {
        if (!(ma & (1u << i))) continue;
        ++leafHits;
        expectSameLane(a, i, b, i);
      }
    }
  }
  EXPECT_GT(leafHits, 1000);
}
#endif

// A Gaussian tested against a packet of 8 rays gives each ray, bit for bit, what the ray
// gets testing the Gaussian's block (with AVX2 too: both against the scalar tests).
TEST(FastTracer, PacketTestsAgreeWithBlockTestsBitForBit) {
  KernelTestScene built(73);
  const Bvh8& bvh = built.tracer.bvh();
  std::vector<TraceRay> rays = randomRays(160, 74);
  int hits = 0;
  for (size_t first = 0; first + kBvhWidth <= rays.size(); first += kBvhWidth) {
    // The packet's rays share the first one's origin; some have zero direction components.
    RayPacket packet;
    std::vector<Bvh8Ray> alone;
    for (int i = 0; i < kBvhWidth; ++i) {
      TraceRay ray = rays[first + size_t(i)];
      ray.origin = rays[first].origin;
      if (i == 7) ray.direction = {0, 0, 1};
      ray.tMin = i == 3 ? 0.5f : 0.0f;
      alone.emplace_back(ray);
      for (int a = 0; a < 3; ++a) packet.direction[a][i] = alone.back().direction[a];
      packet.tMin[i] = ray.tMin;
    }
    for (size_t l = 0; l < bvh.stats().blocks; l += 5) {
      const Bvh8Block& block = bvh.blocks()[l];
      for (int g = 0; g < kBvhWidth; ++g) {
        Bvh8BlockCandidates packetResult;
        uint32_t packetMask = intersectPacketScalar(block, g, alone[0].origin, packet, &packetResult);
#ifdef __AVX2__
        Bvh8BlockCandidates avx2;
        ASSERT_EQ(intersectPacketAvx2(block, g, alone[0].origin, packet, &avx2), packetMask);
#endif
        for (int i = 0; i < kBvhWidth; ++i) {
          Bvh8BlockCandidates blockResult;
          uint32_t blockMask = intersectBlockScalar(block, alone[size_t(i)], &blockResult);
          bool passes = packetMask & (1u << i);
          ASSERT_EQ(passes, bool(blockMask & (1u << g)));
          if (!passes) continue;
          ++hits;
          expectSameLane(packetResult, i, blockResult, g);
#ifdef __AVX2__
          expectSameLane(avx2, i, packetResult, i);
#endif
        }
      }
    }
  }
  EXPECT_GT(hits, 300);
}

// Reflection rays' back-face skipping: the fast tracer matches the reference, and the skip
// really removes hits (Gaussians whose normal points along the ray near the origin).
TEST(FastTracer, BackfaceSkippingMatchesTheReference) {
  GaussianScene scene = randomScene(2000, 31);
  std::vector<TraceRay> rays = randomRays(600, 32);
  for (TraceRay& r : rays) r.backfaceSkip = 1.5f;
  TraceSettings settings;
  FastGaussianTracer tracer;
  tracer.build(scene, settings);
  Traced fast = traceFast(tracer, rays);
  expectSame(fast, traceOracle(scene, settings, rays), 1e-4f, "backface skip 1.5");
  std::vector<TraceRay> plain = rays;
  for (TraceRay& r : plain) r.backfaceSkip = 0;
  Traced unskipped = traceFast(tracer, plain);
  int changed = 0;
  for (size_t i = 0; i < rays.size(); ++i) changed += fast.results[i].hitCount != unskipped.results[i].hitCount;
  EXPECT_GT(changed, int(rays.size() / 4));
}

}  // namespace
}  // namespace glint
