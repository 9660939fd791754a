// The GPU's k-buffer traversal (raytrace/fast/kbuffer_traversal.h), run on the CPU: the same
// hits in the same order as the fast CPU tracer and the same results, bit for bit (with the
// exact tail, the hits behind termination multiply into T_f in another order: to rounding),
// for buffers small enough to need many passes and for the GPU's own size.
#include "raytrace/fast/kbuffer_traversal.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "common/random_gaussians.h"
#include "raytrace/fast/fast_tracer.h"

namespace glint {
namespace {

// traceKBuffer<K> over the fast tracer's own tree, recording into an array as the GPU does.
template <int K>
RayResult traceWithKBuffer(const FastGaussianTracer& fast, const GaussianScene& scene, const TraceRay& ray,
                           std::vector<HitRecord>* hits, bool* overflowed, KBufferTraceStats* stats) {
  const Bvh8& bvh = fast.bvh();
  Bvh8View view{bvh.nodes(), bvh.blocks(), bvh.empty()};
  hits->assign(512, HitRecord{});
  uint32_t count = 0;
  *overflowed = false;
  RayResult r = traceKBuffer<K>(view, GaussianAttributes::of(scene), bvh.settings(), ray,
                                ArrayHitRecorder{hits->data(), uint32_t(hits->size()), &count, overflowed}, stats);
  hits->resize(count);
  return r;
}

bool near(float a, float b) { return std::abs(a - b) <= 1e-5f * std::max(1.0f, std::abs(b)); }

// Within rounding of the final transmittance's product: T_f, and the outputs its tail
// estimate scales.
bool nearlyEqual(const RayResult& a, const RayResult& b) {
  return near(a.diffuse.x, b.diffuse.x) && near(a.diffuse.y, b.diffuse.y) && near(a.diffuse.z, b.diffuse.z) &&
         near(a.depth, b.depth) && near(a.roughness, b.roughness) && near(a.normalLength, b.normalLength) &&
         std::abs(a.transmittance - b.transmittance) <= 1e-5f * b.transmittance + 1e-12f && a.hitCount == b.hitCount &&
         a.truncated == b.truncated;
}

bool bitEqual(const RayResult& a, const RayResult& b) {
  return std::memcmp(&a.diffuse, &b.diffuse, sizeof(Rgb)) == 0 && std::memcmp(&a.normal, &b.normal, sizeof(Vec3f)) == 0 &&
         std::memcmp(&a.f0, &b.f0, sizeof(Rgb)) == 0 && std::memcmp(&a.depth, &b.depth, sizeof(float)) == 0 &&
         std::memcmp(&a.roughness, &b.roughness, sizeof(float)) == 0 &&
         std::memcmp(&a.transmittance, &b.transmittance, sizeof(float)) == 0 &&
         std::memcmp(&a.normalLength, &b.normalLength, sizeof(float)) == 0 && a.hitCount == b.hitCount &&
         a.truncated == b.truncated;
}

template <int K>
void expectSameAsFastTracer(const GaussianScene& scene, const std::vector<TraceRay>& rays,
                            const TraceSettings& settings, const std::string& what, int* passes) {
  FastGaussianTracer fast;
  fast.build(scene, settings);
  ASSERT_TRUE(fitsKBufferStack(fast.bvh()));
  int failures = 0;
  KBufferTraceStats stats;
  for (size_t i = 0; i < rays.size() && failures < 5; ++i) {
    HitList want;
    RayResult expected = fast.trace(rays[i], &want);
    std::vector<HitRecord> got;
    bool overflowed = false;
    RayResult r = traceWithKBuffer<K>(fast, scene, rays[i], &got, &overflowed, &stats);
    bool same = (settings.exactTail ? nearlyEqual(r, expected) : bitEqual(r, expected)) &&
                got.size() == want.hits.size() && overflowed == want.overflowed;
    for (size_t k = 0; same && k < got.size(); ++k)
      same = got[k].id == want.hits[k].id && got[k].t == want.hits[k].t && got[k].alpha == want.hits[k].alpha;
    if (!same) {
      ++failures;
      ADD_FAILURE() << what << " K=" << K << ", ray " << i << ": depth " << r.depth << " vs " << expected.depth
                    << ", T " << r.transmittance << " vs " << expected.transmittance << ", hits " << r.hitCount
                    << " vs " << expected.hitCount << " (lists " << got.size() << " vs " << want.hits.size() << ")";
    }
  }
  *passes += stats.passes;
}

TEST(KBufferTraversal, BitIdenticalToTheFastTracerOnRandomScenes) {
  GaussianScene scene = randomScene(2000, 41);
  std::vector<TraceRay> rays = randomRays(600, 42);
  int smallPasses = 0, largePasses = 0;
  for (const TraceSettings& settings : traceSettingsGrid({1.0f, 2.0f, 2.5f})) {
    expectSameAsFastTracer<3>(scene, rays, settings, describe(settings), &smallPasses);
    expectSameAsFastTracer<32>(scene, rays, settings, describe(settings), &largePasses);
  }
  // A 3-hit buffer needs many passes per ray (the multi-pass path is exercised), the GPU's
  // 32 far fewer.
  EXPECT_GT(smallPasses, 12 * 5 * int(rays.size()));
  EXPECT_LT(largePasses, smallPasses / 4);
}

TEST(KBufferTraversal, BackfaceSkippingAndTMinAsTheFastTracer) {
  GaussianScene scene = randomScene(2000, 43);
  std::vector<TraceRay> rays = randomRays(600, 44);
  for (size_t i = 0; i < rays.size(); i += 2) rays[i].backfaceSkip = 1.5f;
  int passes = 0;
  expectSameAsFastTracer<kGpuKBufferHits>(scene, rays, TraceSettings{}, "backface skip", &passes);
}

// The scene, rays and settings of the GPU test (tests/cuda), whose CPU side this is.
TEST(KBufferTraversal, TheGpuTestsRaysAsTheFastTracer) {
  GaussianScene scene = randomScene(20000, 51);
  TraceSettings settings;
  settings.minTransmittance = 1e-3f;
  std::vector<TraceRay> rays = randomRays(10000, 52);
  for (size_t i = 0; i < rays.size(); i += 4) rays[i].backfaceSkip = 0.5f;
  int passes = 0;
  expectSameAsFastTracer<kGpuKBufferHits>(scene, rays, settings, "gpu config", &passes);
}
TEST(KBufferTraversal, EmptyAndTransparentScenes) {
  int passes = 0;
  std::vector<TraceRay> rays = randomRays(60, 45);
  expectSameAsFastTracer<8>(GaussianScene{}, rays, TraceSettings{}, "empty scene", &passes);
  GaussianScene faint = randomScene(300, 46);
  for (float& o : faint.opacityLogit) o = logit(0.004f);  // below alphaMin everywhere: no proxies
  expectSameAsFastTracer<8>(faint, rays, TraceSettings{}, "faint scene", &passes);
}

TEST(KBufferTraversal, NearestHitsKeepsTheKNearestInOrder) {
  NearestHits<4> buffer;
  const float keys[] = {5, 1, 4, 1, 3, 9, 0.5f, 2};
  bool lost = false;
  for (uint32_t i = 0; i < 8; ++i) buffer.insert({keys[i], i, 0.5f}, &lost);
  ASSERT_EQ(buffer.size(), 4);
  // (0.5, 6), (1, 1), (1, 3), (2, 7): ties by id.
  EXPECT_EQ(buffer[0].id, 6u);
  EXPECT_EQ(buffer[1].id, 1u);
  EXPECT_EQ(buffer[2].id, 3u);
  EXPECT_EQ(buffer[3].id, 7u);
  EXPECT_TRUE(buffer.full());
  EXPECT_TRUE(lost);  // 8 hits in 4 places
  // Where a hit goes: nowhere behind the farthest of a full buffer, else its place.
  EXPECT_EQ(buffer.insert({9.0f, 9, 0.5f}, &lost), -1);
  EXPECT_EQ(buffer.insert({0.1f, 10, 0.5f}, &lost), 0);
  EXPECT_EQ(buffer[0].id, 10u);
  NearestHits<4> roomy;
  bool roomyLost = false;
  EXPECT_EQ(roomy.insert({2.0f, 0, 0.5f}, &roomyLost), 0);
  EXPECT_EQ(roomy.insert({1.0f, 1, 0.5f}, &roomyLost), 0);
  EXPECT_EQ(roomy.insert({3.0f, 2, 0.5f}, &roomyLost), 2);
  EXPECT_FALSE(roomyLost);
}

}  // namespace
}  // namespace glint
