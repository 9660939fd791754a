// traceBatch against trace() ray by ray, with hit lists, on every tracer: camera rays (the
// fast tracer's bundles) from inside and outside a cloud, scattered rays like reflected
// segments (with tMin and back-face skipping), and hit buffers and hit lists too small
// for the rays (overflow). Batched and per-ray tracing composite the same hits in the
// same order, so results agree to float rounding and hit lists exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/camera_rays.h"
#include "common/random_gaussians.h"
#include "math/rng.h"
#include "raytrace/fast/fast_tracer.h"
#include "raytrace/gaussian_tracer.h"

namespace glint {
namespace {

using test::cameraRays;

// Rays from scattered origins in the cloud in random directions, as reflected segments
// are: some with a tMin, all skipping back faces near their origin.
std::vector<TraceRay> scatteredRays(size_t n, uint64_t seed) {
  Rng rng(seed);
  std::vector<TraceRay> rays;
  for (size_t i = 0; i < n; ++i) {
    Vec3f o(uniform(rng, -0.9f, 0.9f), uniform(rng, -0.9f, 0.9f), uniform(rng, -0.9f, 0.9f));
    rays.push_back({o, randomDirection(rng), i % 3 == 0 ? 0.05f : 0.0f, 0.1f});
  }
  return rays;
}

void expectSame(const GaussianTracer& tracer, const std::vector<TraceRay>& rays, size_t hitCapacity,
                const std::string& what) {
  std::vector<RayResult> batched(rays.size());
  std::vector<HitList> batchedHits(rays.size());
  for (HitList& h : batchedHits) h.capacity = hitCapacity;
  tracer.traceBatch(rays, batched, batchedHits);
  std::vector<RayResult> plain(rays.size());
  tracer.traceBatch(rays, plain);  // without hit lists
  int failures = 0, overflowed = 0, hits = 0;
  for (size_t i = 0; i < rays.size() && failures < 5; ++i) {
    HitList single;
    single.capacity = hitCapacity;
    RayResult want = tracer.trace(rays[i], &single);
    for (const RayResult* got : {&batched[i], &plain[i]}) {
      const float tol = 1e-5f;
      bool same = std::abs(got->diffuse.x - want.diffuse.x) <= tol && std::abs(got->depth - want.depth) <= tol * 10 &&
                  std::abs(got->normal.y - want.normal.y) <= tol && std::abs(got->transmittance - want.transmittance) <= tol &&
                  std::abs(got->roughness - want.roughness) <= tol && std::abs(got->f0.z - want.f0.z) <= tol &&
                  got->hitCount == want.hitCount && got->truncated == want.truncated;
      if (!same) {
        ++failures;
        ADD_FAILURE() << what << " ray " << i << ": diffuse " << got->diffuse.x << " vs " << want.diffuse.x
                      << ", hits " << got->hitCount << " vs " << want.hitCount;
      }
    }
    const HitList& b = batchedHits[i];
    EXPECT_EQ(b.overflowed, single.overflowed) << what << " ray " << i;
    ASSERT_EQ(b.hits.size(), single.hits.size()) << what << " ray " << i;
    for (size_t k = 0; k < b.hits.size(); ++k) {
      EXPECT_EQ(b.hits[k].id, single.hits[k].id) << what << " ray " << i << " hit " << k;
      EXPECT_NEAR(b.hits[k].t, single.hits[k].t, 1e-6f * std::max(1.0f, std::abs(single.hits[k].t)));
      EXPECT_NEAR(b.hits[k].alpha, single.hits[k].alpha, 1e-6f);
    }
    overflowed += single.overflowed;
    hits += int(single.hits.size());
  }
  EXPECT_GT(hits, int(rays.size())) << what << ": the rays must composite hits";
  if (hitCapacity < 8) {
    EXPECT_GT(overflowed, 0) << what << ": the small lists must overflow";
  }
}

struct TracerCase {
  std::string name;
  std::function<std::unique_ptr<GaussianTracer>()> make;
};

class TraceBatch : public ::testing::TestWithParam<int> {};

std::vector<TracerCase> tracerCases() {
  return {{"fast", [] { return std::unique_ptr<GaussianTracer>(std::make_unique<FastGaussianTracer>()); }},
          // Hit buffers of 4: the bundles hand rays back and the traversal runs extra passes.
          {"fast, small hit buffers",
           [] { return std::unique_ptr<GaussianTracer>(std::make_unique<FastGaussianTracer>(4)); }},
          {"embree-k16", [] { return makeGaussianTracer("embree-k16"); }},
          {"reference", [] { return makeGaussianTracer("reference"); }}};
}

TEST_P(TraceBatch, GivesWhatEachRayTracedAloneGives) {
  const TracerCase c = tracerCases()[size_t(GetParam())];
  const bool reference = c.name == "reference";
  GaussianScene scene = randomScene(reference ? 400 : 3000, 11);
  TraceSettings settings;
  settings.kernelPower = 2.0f;
  std::unique_ptr<GaussianTracer> tracer = c.make();
  tracer->build(scene, settings);
  const int side = reference ? 12 : 24;
  for (size_t capacity : {size_t(512), size_t(4)}) {
    std::string suffix = " (" + c.name + ", hit lists of " + std::to_string(capacity) + ")";
    expectSame(*tracer, cameraRays({0.1f, 0.2f, 3.5f}, {0, 0, 0}, side, side, 1), capacity, "outside" + suffix);
    expectSame(*tracer, cameraRays({0.05f, -0.1f, 0.2f}, {0.5f, 0.3f, -1.0f}, side, side, 2), capacity,
               "inside" + suffix);
    expectSame(*tracer, scatteredRays(size_t(side * side), 3), capacity, "scattered" + suffix);
  }
}

std::string caseName(const ::testing::TestParamInfo<int>& info) {
  static const char* const kNames[] = {"Fast", "FastSmallHitBuffers", "EmbreeK16", "Reference"};
  return kNames[info.param];
}

INSTANTIATE_TEST_SUITE_P(EveryTracer, TraceBatch, ::testing::Range(0, 4), caseName);

}  // namespace
}  // namespace glint
