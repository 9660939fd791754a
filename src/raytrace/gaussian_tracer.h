// The one small interface every Gaussian tracer implements (the fast CPU BVH, the Embree
// k-buffer baseline, the double-precision reference; later a GPU backend). Training,
// rendering and editing code talk only to this.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "math/vec.h"
#include "raytrace/ray_result.h"
#include "raytrace/trace_settings.h"
#include "scene/gaussians.h"

namespace glint {

struct TraceRay {
  Vec3f origin;
  Vec3f direction;  // unit length
  float tMin = 0;   // hits whose proxy ends before tMin are ignored
  // Hits closer than this to the origin whose Gaussian's normal points along the ray are
  // ignored (reflection rays, against self-occlusion; paper appendix B). 0 = none.
  float backfaceSkip = 0;
};

// What a caller knows of a batch's rays: camera rays of whole images, many sharing an
// origin and pointing close together (the fast tracer bundles them), or scattered rays
// (reflected segments, or pixels drawn at random over an image: bundles of those gather
// candidates for a wide cone that few of their rays hit, and measured slower than tracing
// each ray alone in train_bench).
enum class RayCoherence { Coherent, Scattered };

class GaussianTracer {
 public:
  virtual ~GaussianTracer() = default;
  virtual const char* name() const = 0;

  // Builds the acceleration structure. The scene is referenced, not copied: it must stay
  // alive and unchanged in size until the next build.
  virtual void build(const GaussianScene& scene, const TraceSettings& settings) = 0;
  // Updates the structure after parameters (not the count) changed.
  virtual void refit() = 0;
  // Traces one ray; thread-safe. hits, if given, receives the composited hits in order.
  virtual RayResult trace(const TraceRay& ray, HitList* hits = nullptr) const = 0;
  // Traces many rays in parallel (the default splits them over parallelFor), with the
  // results of trace() to rounding. hits, if not empty, holds one list per ray (its
  // capacity set by the caller) and receives each ray's composited hits, as trace() does.
  virtual void traceBatch(std::span<const TraceRay> rays, std::span<RayResult> results,
                          std::span<HitList> hits = {}, RayCoherence coherence = RayCoherence::Coherent) const;
  // Bytes held by the acceleration structure (for benchmarks).
  virtual size_t memoryBytes() const = 0;
};

// "fast" (our wide BVH), "embree-k16" (3DGRT-style baseline) or "reference" (every ray
// against every Gaussian, in double precision). Throws Error for another name. Defined in
// src/tracers/ (link glint_tracers), which links Embree for the baseline; glint_raytrace
// itself does not.
std::unique_ptr<GaussianTracer> makeGaussianTracer(const std::string& kind);
std::vector<std::string> gaussianTracerNames();
// Whether the tracer of that name traces on the GPU ("cuda", "cuda-warp").
bool isGpuTracer(const std::string& kind);

}  // namespace glint
