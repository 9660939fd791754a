// The fast CPU Gaussian tracer: an 8-wide BVH over the proxy boxes with AVX2 node and
// leaf tests, traversed once with the nearest-entry subtree first, compositing hits in
// exact front-to-back order as soon as no pending subtree can still hold a nearer one,
// and stopping when the ray's transmittance falls below the threshold.
#pragma once

#include <cstdint>

#include "raytrace/fast/bvh8.h"
#include "raytrace/gaussian_tracer.h"

namespace glint {

// What a ray cost (for tests and benchmarks).
struct FastTraceStats {
  int passes = 0;             // traversals (more than 1 only when the hit buffer overflowed)
  int64_t nodes = 0;          // inner nodes visited
  int64_t leaves = 0;         // 8-lane leaf blocks tested
  int64_t evaluations = 0;    // Gaussians whose proxy the ray crosses (kernel evaluated)
};

class FastGaussianTracer final : public GaussianTracer {
 public:
  static constexpr int kDefaultHitBufferCapacity = 128;
  static constexpr int kMaxHitBufferCapacity = 256;
  static constexpr int kDefaultBundleRays = 64;

  // hitBufferCapacity (2 to kMaxHitBufferCapacity) bounds the hits a ray holds while
  // waiting to be composited; when a ray needs more, it keeps the nearest, composites
  // them, and traverses again for the rest. Tests set it small to exercise that path.
  explicit FastGaussianTracer(int hitBufferCapacity = kDefaultHitBufferCapacity);

  const char* name() const override { return "fast"; }
  void build(const GaussianScene& scene, const TraceSettings& settings) override;
  void refit() override;
  RayResult trace(const TraceRay& ray, HitList* hits = nullptr) const override;
  // The same, also reporting what the ray cost (added to *stats).
  RayResult trace(const TraceRay& ray, HitList* hits, FastTraceStats* stats) const;
  // Rays that share an origin are ordered by direction and traced in bundles of
  // kBundleRays (ray_bundle.h): the bundle gathers its candidate Gaussians once and each
  // ray composites them in the same exact order as trace(). Other rays go one by one.
  // Scattered batches are traced ray by ray.
  void traceBatch(std::span<const TraceRay> rays, std::span<RayResult> results, std::span<HitList> hits = {},
                  RayCoherence coherence = RayCoherence::Coherent) const override;
  // Bundle size (tests set it; 0 turns bundles off and traces every ray alone).
  void setBundleRays(int rays) { bundleRays_ = rays; }
  size_t memoryBytes() const override { return bvh_.memoryBytes(); }
  // Scratch memory of a thread while tracing (benchmarks report it): a ray's traversal
  // state (its hit buffer, pending subtrees and compositor), and a bundle's per-ray hit
  // buffers and compositors (without its candidate list, which grows with the scene).
  static size_t rayScratchBytes();
  static size_t bundleScratchBytes();
  static size_t threadScratchBytes() { return rayScratchBytes() + bundleScratchBytes(); }

  const Bvh8& bvh() const { return bvh_; }

 private:
  Bvh8 bvh_;
  int hitBufferCapacity_;
  int bundleRays_ = kDefaultBundleRays;
  bool built_ = false;
};

}  // namespace glint
