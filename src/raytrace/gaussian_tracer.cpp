// The default batch tracing of GaussianTracer: rays split over the parallel loop.
#include "raytrace/gaussian_tracer.h"

#include "core/error.h"
#include "core/parallel.h"

namespace glint {

void GaussianTracer::traceBatch(std::span<const TraceRay> rays, std::span<RayResult> results,
                                std::span<HitList> hits, RayCoherence) const {
  GLINT_CHECK(rays.size() == results.size(), "traceBatch: one result per ray");
  GLINT_CHECK(hits.empty() || hits.size() == rays.size(), "traceBatch: one hit list per ray, or none");
  parallelForChunks(int64_t(rays.size()), 64, [&](int64_t begin, int64_t end) {
    for (int64_t i = begin; i < end; ++i) results[i] = trace(rays[i], hits.empty() ? nullptr : &hits[size_t(i)]);
  });
}

}  // namespace glint
