// The baseline Gaussian tracer the fast one is measured against: the 3DGRT algorithm
// (Moenne-Loccoz et al. 2024, "3D Gaussian Ray Tracing", section 4) on Embree 3. Each
// Gaussian's proxy AABB is a primitive of one Embree user geometry; the intersect callback
// evaluates the kernel and keeps the k = 16 nearest hits in a sorted per-ray buffer while
// rejecting every hit, so traversal visits them all (the "any-hit" scheme). The buffer is
// then composited front to back, and traversal is repeated from the last composited hit
// until the ray terminates or runs out of hits.
#pragma once

#include <cstdint>
#include <memory>

#include "raytrace/gaussian_tracer.h"

namespace glint {

// What a ray cost (for tests and benchmarks).
struct EmbreeTraceStats {
  int rounds = 0;           // traversals with the k-buffer (the exact-tail pass excluded)
  int64_t evaluations = 0;  // intersect callbacks (proxy boxes reached) over all passes
};

class EmbreeK16Tracer final : public GaussianTracer {
 public:
  static constexpr int kBufferSize = 16;

  // How Embree builds and updates the BVH. (RTC_BUILD_QUALITY_HIGH is not offered: for user
  // geometry Embree 3.13 builds the same tree as MEDIUM, same callbacks per ray, same memory.)
  enum class BvhMode {
    // One-level scene, RTC_BUILD_QUALITY_MEDIUM; refit() rebuilds. The fastest to trace.
    kMedium,
    // A dynamic two-level scene (scene quality LOW) whose Gaussian BVH has geometry quality
    // RTC_BUILD_QUALITY_REFIT: refit() only recomputes the node boxes (2-3x faster than a
    // rebuild), but this tree costs ~3x the callbacks per ray, traces ~25% slower, and
    // keeps the topology of the first build as Gaussians move.
    kRefit,
  };

  explicit EmbreeK16Tracer(BvhMode mode = BvhMode::kMedium);
  ~EmbreeK16Tracer() override;
  EmbreeK16Tracer(const EmbreeK16Tracer&) = delete;
  EmbreeK16Tracer& operator=(const EmbreeK16Tracer&) = delete;

  const char* name() const override { return "embree-k16"; }
  // Throws Error when Embree fails (e.g. out of memory).
  void build(const GaussianScene& scene, const TraceSettings& settings) override;
  // Recomputes every proxy from the scene's current parameters. When the set of Gaussians
  // that can contribute (proxy radius > 0) changed, this is a full build.
  void refit() override;
  RayResult trace(const TraceRay& ray, HitList* hits = nullptr) const override;
  // The same, also reporting what the ray cost.
  RayResult trace(const TraceRay& ray, HitList* hits, EmbreeTraceStats* stats) const;
  // Embree's current allocations (counted by a device memory monitor) plus our
  // per-Gaussian frames and primitive-to-Gaussian map.
  size_t memoryBytes() const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace glint
