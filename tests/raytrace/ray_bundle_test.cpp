// Tests of the fast tracer's coherent ray bundles: the cone culling is conservative, and
// batches of camera rays traced in bundles give what each ray traced alone gives (and
// what the double-precision reference gives).
#include "raytrace/fast/ray_bundle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common/camera_rays.h"
#include "common/random_gaussians.h"
#include "math/rng.h"
#include "raytrace/fast/fast_tracer.h"
#include "raytrace/reference/reference_tracer.h"

namespace glint {
namespace {

using test::cameraRays;

bool nearBundle(float a, float b, float tolerance) { return std::abs(a - b) <= tolerance * std::max(1.0f, std::abs(b)); }
bool nearBundle(const Vec3f& a, const Vec3f& b, float tolerance) {
  return nearBundle(a.x, b.x, tolerance) && nearBundle(a.y, b.y, tolerance) && nearBundle(a.z, b.z, tolerance);
}

void expectSameResults(const std::vector<RayResult>& got, const std::vector<RayResult>& want, float tolerance,
                       const std::string& what) {
  int failures = 0;
  for (size_t i = 0; i < want.size() && failures < 5; ++i) {
    const RayResult &a = got[i], &b = want[i];
    bool same = nearBundle(a.diffuse, b.diffuse, tolerance) && nearBundle(a.depth, b.depth, tolerance) &&
                nearBundle(a.normal, b.normal, tolerance) && nearBundle(a.roughness, b.roughness, tolerance) &&
                nearBundle(a.f0, b.f0, tolerance) && nearBundle(a.transmittance, b.transmittance, tolerance) &&
                a.hitCount == b.hitCount && a.truncated == b.truncated;
    if (!same) {
      ++failures;
      ADD_FAILURE() << what << ", ray " << i << ": diffuse " << a.diffuse.x << " vs " << b.diffuse.x << ", depth "
                    << a.depth << " vs " << b.depth << ", T " << a.transmittance << " vs " << b.transmittance
                    << ", hits " << a.hitCount << " vs " << b.hitCount;
    }
  }
}

// Camera batches: outside the cloud, inside it (Gaussians behind the eye and around it),
// inside with tMin > 0, and a batch of rays with one origin but all directions (no bundle
// can hold them).
std::vector<std::pair<std::string, std::vector<TraceRay>>> cameraBatches() {
  std::vector<std::pair<std::string, std::vector<TraceRay>>> batches;
  batches.push_back({"outside", cameraRays({0.3f, 0.4f, 3.0f}, {0, 0, 0}, 48, 40, 1)});
  batches.push_back({"inside", cameraRays({0.1f, -0.2f, 0.05f}, {0.5f, 0.3f, -1.0f}, 48, 40, 2)});
  batches.push_back({"inside, tMin 0.3", cameraRays({-0.2f, 0.1f, 0.3f}, {0.0f, -0.4f, 1.0f}, 40, 32, 3, 0.3f)});
  Rng rng(4);
  std::vector<TraceRay> spread;
  for (int i = 0; i < 500; ++i) spread.push_back({{0.2f, 0.2f, 0.2f}, randomDirection(rng), 0.0f});
  batches.push_back({"all directions", spread});
  return batches;
}

TEST(RayBundle, SphereConeTestsNeverRejectASphereARayOfTheConeMeets) {
  Rng rng(7);
  int met = 0, rejected = 0, laneRejected = 0;
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<TraceRay> rays;
    Vec3f apex(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
    Vec3f axis = randomDirection(rng);
    for (int k = 0; k < 16; ++k) rays.push_back({apex, normalize(axis + randomDirection(rng) * 0.05f), 0.0f});
    std::vector<uint32_t> order(rays.size());
    for (uint32_t k = 0; k < order.size(); ++k) order[k] = k;
    RayCone cone;
    ASSERT_TRUE(boundingCone(rays, order, &cone));
    // The 8-lane form of the test, with the cone in one lane of a packet's cones.
    const int lane = trial % kBvhWidth;
    PacketCones lanes;
    for (int l = 0; l < kBvhWidth; ++l) {
      Vec3f other = l == lane ? cone.axis : randomDirection(rng);
      for (int a = 0; a < 3; ++a) lanes.axis[a][l] = other[a];
      lanes.cosAngle[l] = l == lane ? cone.cosAngle : 1.0f;
      lanes.sinAngle[l] = l == lane ? cone.sinAngle : 0.0f;
    }
    for (int s = 0; s < 200; ++s) {
      Vec3f center = apex + axis * uniform(rng, -1.0f, 4.0f) + randomDirection(rng) * uniform(rng, 0.0f, 0.5f);
      float radius = uniform(rng, 0.001f, 0.2f);
      bool hit = false;
      for (const TraceRay& ray : rays) {
        // Ray-sphere in double: the nearest point of the ray (t >= 0) to the centre.
        Vec3d v = Vec3d(center - ray.origin), d = Vec3d(normalize(ray.direction));
        double t = std::max(0.0, dot(v, d));
        hit = hit || length(v - d * t) <= double(radius);
      }
      bool meets = sphereMeetsCone(center, radius, cone);
      bool laneMeets = conesMeetingSphere(lanes, cone.apex, center, radius) & (1u << lane);
      if (hit) {
        ++met;
        EXPECT_TRUE(meets) << "trial " << trial << " sphere " << s;
        EXPECT_TRUE(laneMeets) << "trial " << trial << " sphere " << s << " (8 lanes)";
      }
      if (!meets) ++rejected;
      if (!laneMeets) ++laneRejected;
    }
  }
  EXPECT_GT(met, 1000);       // the test saw many spheres the rays meet
  EXPECT_GT(rejected, 10000);  // and the cone culls most of the others
  EXPECT_GT(laneRejected, 10000);
}

TEST(RayBundle, BundledBatchesMatchRaysTracedAloneAndTheReference) {
  GaussianScene scene = randomScene(2000, 31);
  for (float power : {1.0f, 3.0f}) {
    for (bool exactTail : {false, true}) {
      TraceSettings settings;
      settings.kernelPower = power;
      settings.minTransmittance = 1e-4f;
      settings.exactTail = exactTail;
      FastGaussianTracer tracer;
      tracer.build(scene, settings);
      ReferenceTracer reference;
      reference.build(scene, settings);
      for (const auto& [name, rays] : cameraBatches()) {
        std::string what = name + " p=" + std::to_string(int(power)) + (exactTail ? " exact tail" : "");
        std::vector<RayResult> bundled(rays.size()), alone(rays.size()), oracle(rays.size());
        for (size_t i = 0; i < rays.size(); ++i) alone[i] = tracer.trace(rays[i]);
        for (size_t i = 0; i < rays.size(); ++i) oracle[i] = reference.trace(rays[i]);
        // 2 packets of 8 rays; 13 packets in 2 groups of cones, the last packet half full.
        for (int bundleRays : {16, 100}) {
          std::string bundle = what + ", bundles of " + std::to_string(bundleRays);
          tracer.setBundleRays(bundleRays);
          tracer.traceBatch(rays, bundled);
          // The same hits in the same order; only the exact tail multiplies in another order.
          expectSameResults(bundled, alone, exactTail ? 1e-5f : 1e-6f, bundle + " (bundled vs alone)");
          expectSameResults(bundled, oracle, 1e-4f, bundle + " (bundled vs reference)");
        }
      }
    }
  }
}

// Indices of the rays, all within the bundling range, ordered by direction (8x8 tiles).
std::vector<uint32_t> directionOrder(const std::vector<TraceRay>& rays) {
  std::vector<uint32_t> order(rays.size());
  for (uint32_t k = 0; k < order.size(); ++k) order[k] = k;
  EXPECT_EQ(orderByDirection(rays, order), rays.size());
  return order;
}

// The Gaussians of the current chunk's blocks (a multiset, so duplicates would show).
std::multiset<uint32_t> candidateIds(const BundleCandidates& candidates) {
  std::multiset<uint32_t> ids;
  for (int k = 0; k < candidates.blockCount(); ++k)
    for (int lane = 0; lane < kBvhWidth; ++lane)
      if (candidates.block(k).radius2[lane] >= 0.0f) ids.insert(candidates.block(k).id[lane]);
  return ids;
}

// Every hit of the rays[tile] through the whole cloud, from the reference tracer.
std::vector<HitRecord> referenceHits(const ReferenceTracer& reference, const std::vector<TraceRay>& rays,
                                     std::span<const uint32_t> tile) {
  std::vector<HitRecord> all;
  for (uint32_t k : tile) {
    HitList hits;
    hits.capacity = 100000;
    reference.trace(rays[k], &hits);
    all.insert(all.end(), hits.hits.begin(), hits.hits.end());
  }
  return all;
}

TEST(RayBundle, CandidatesHoldEveryGaussianTheBundlesRaysHitAndFewOthers) {
  GaussianScene scene = randomScene(2000, 41);
  TraceSettings settings;
  settings.minTransmittance = 0.0f;  // every hit, to the far side
  FastGaussianTracer tracer;
  tracer.build(scene, settings);
  ReferenceTracer reference;
  reference.build(scene, settings);
  std::vector<TraceRay> rays = cameraRays({0.0f, 0.0f, 2.5f}, {0, 0, 0}, 64, 64, 5);
  std::vector<uint32_t> order = directionOrder(rays);
  // The first 64 rays in direction order form a compact tile.
  std::span<const uint32_t> tile(order.data(), 64);
  RayCone cone;
  ASSERT_TRUE(boundingCone(rays, tile, &cone));
  EXPECT_LT(std::acos(cone.cosAngle), 0.09f);  // an 8x8 tile of 64x64 pixels at 60 degrees: 0.08 rad
  BundleCandidates candidates;
  candidates.gather(tracer.bvh(), cone);
  std::multiset<uint32_t> gathered = candidateIds(candidates);
  EXPECT_EQ(gathered.size(), candidates.candidates());
  std::vector<HitRecord> hits = referenceHits(reference, rays, tile);
  for (const HitRecord& h : hits) EXPECT_TRUE(gathered.count(h.id)) << "Gaussian " << h.id << " is hit but no candidate";
  EXPECT_GT(hits.size(), 64u);
  EXPECT_LT(candidates.candidates(), scene.size() / 4);  // the cone culls most of the cloud
  // The bounds are suffix minima: never increasing from block to block.
  for (int k = 1; k < candidates.blockCount(); ++k) EXPECT_LE(candidates.blockBound(k - 1), candidates.blockBound(k));
}

TEST(RayBundle, ChunksPartitionTheCandidatesAndEachFrontierBoundsTheLaterChunks) {
  GaussianScene scene = randomScene(2000, 47);
  TraceSettings settings;
  FastGaussianTracer tracer;
  tracer.build(scene, settings);
  std::vector<TraceRay> rays = cameraRays({0.0f, 0.0f, 2.5f}, {0, 0, 0}, 64, 64, 5);
  std::vector<uint32_t> order = directionOrder(rays);
  RayCone cone;
  // Morton position 2048 starts the 8x8 tile at the image centre, which sees the cloud's depth.
  std::span<const uint32_t> tile(order.data() + 2048, 64);
  ASSERT_TRUE(boundingCone(rays, tile, &cone));

  BundleCandidates all;
  all.gather(tracer.bvh(), cone);
  std::multiset<uint32_t> wanted = candidateIds(all);
  EXPECT_EQ(all.frontier(), std::numeric_limits<float>::infinity());

  // Chunks of at least 4: together they hold each candidate once, and no ray of the cone
  // hits a Gaussian of a later chunk with a key below an earlier chunk's frontier.
  BundleCandidates chunked;
  chunked.start(tracer.bvh(), cone);
  std::multiset<uint32_t> got;
  std::map<uint32_t, float> frontierBefore;  // Gaussian id -> frontier of the chunk before its own
  float previousFrontier = cone.tMin;
  int chunks = 0;
  while (chunked.next(4)) {
    ++chunks;
    for (int k = 0; k < chunked.blockCount(); ++k) EXPECT_LE(chunked.blockBound(k), chunked.frontier());
    for (uint32_t id : candidateIds(chunked)) {
      got.insert(id);
      frontierBefore[id] = previousFrontier;
    }
    EXPECT_GE(chunked.frontier(), previousFrontier);
    previousFrontier = chunked.frontier();
  }
  EXPECT_GT(chunks, 3) << all.candidates() << " candidates";
  EXPECT_EQ(chunked.frontier(), std::numeric_limits<float>::infinity());
  EXPECT_EQ(got, wanted);

  ReferenceTracer reference;
  reference.build(scene, settings);
  std::vector<HitRecord> hits = referenceHits(reference, rays, tile);
  for (const HitRecord& h : hits) {
    ASSERT_TRUE(frontierBefore.count(h.id)) << "Gaussian " << h.id << " hit but never gathered";
    EXPECT_GE(h.t, frontierBefore[h.id]) << "Gaussian " << h.id << " hit before its chunk's frontier";
  }
  EXPECT_GT(hits.size(), 64u);
}

TEST(RayBundle, OverflowingBundlesFallBackToTheTraversalAndGiveTheSameImage) {
  GaussianScene scene = randomScene(2000, 51);
  TraceSettings settings;
  settings.minTransmittance = 1e-4f;
  FastGaussianTracer normal, small(2);
  normal.build(scene, settings);
  small.build(scene, settings);
  for (const auto& [name, rays] : cameraBatches()) {
    std::vector<RayResult> want(rays.size()), got(rays.size());
    normal.traceBatch(rays, want);
    small.traceBatch(rays, got);
    expectSameResults(got, want, 1e-6f, name + " capacity 2");
  }
}

}  // namespace
}  // namespace glint
